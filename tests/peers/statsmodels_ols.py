"""Reference for bumpsim's regression: statsmodels OLS and its influence measures.

Usage: statsmodels_ols.py DESIGN_FILE
The file holds a header `y,x1,x2,...` (the model matrix columns after y,
intercept included) and one row per run. Prints JSON: params, bse,
conf_int, rsquared, rsquared_adj, press (from the leave-one-out residuals).
"""
import json
import sys

import numpy as np
import statsmodels.api as sm

data = np.loadtxt(sys.argv[1], delimiter=",", skiprows=1, ndmin=2)
y, x = data[:, 0], data[:, 1:]
fit = sm.OLS(y, x).fit()
influence = fit.get_influence()
press = float(np.sum(influence.resid_press ** 2))
print(json.dumps({
    "params": fit.params.tolist(),
    "bse": fit.bse.tolist(),
    "conf_int": fit.conf_int(0.05).tolist(),
    "rsquared": float(fit.rsquared),
    "rsquared_adj": float(fit.rsquared_adj),
    "press": press,
}))
