"""Independent check of an LS-DYNA deck written by `bumpsim export lsdyna`:
ansys-dyna-core parses it; prints JSON with the keywords it could not
process, validate() errors, ids referenced but not defined, and the force
curve. Usage: dyna_deck.py DECK.k [EXTERNAL_NODE_ID ...] (external nodes are
the user's attachment or spring nodes, defined in the model the include goes into)."""
import json
import sys

from ansys.dyna.core import Deck


def column(keyword, frame, name):
    data = getattr(keyword, frame)
    return [int(v) for v in data[name].dropna().tolist()]


def main():
    path, external = sys.argv[1], {int(a) for a in sys.argv[2:]}
    deck = Deck()
    loaded = deck.loads(open(path).read())
    kinds = {}
    for k in deck.keywords:
        kinds.setdefault(type(k).__name__, []).append(k)
    nodes = {n for k in kinds.get("Node", []) for n in column(k, "nodes", "nid")}
    parts = {int(v) for p in kinds.get("Part", []) for v in p.parts["pid"].dropna()}
    sections = {int(s.secid) for k, ss in kinds.items() if k.startswith("Section") for s in ss}
    sets = {int(s.sid) for s in kinds.get("SetNodeList", [])}
    materials = {int(m.mid) for k, ms in kinds.items() if k.startswith("Mat") for m in ms}
    curves = {int(c.lcid): c for c in kinds.get("DefineCurve", [])}
    undefined = []

    def need(kind, ids, known):
        undefined.extend(f"{kind} {i}" for i in ids if i not in known)

    # this parser reads one row per *ELEMENT_MASS: bumpsim writes one per mass
    masses = [int(m.nid) for m in kinds.get("ElementMass", [])]
    need("node", masses, nodes)
    orientations = {int(v) for o in kinds.get("DefineSdOrientation", []) for v in o.vectors["vid"].dropna()}
    for e in kinds.get("ElementDiscrete", []):
        ends = column(e, "elements", "n1") + column(e, "elements", "n2")
        need("node", [n for n in ends if n not in external], nodes)
        need("part", column(e, "elements", "pid"), parts)
        need("orientation", [v for v in column(e, "elements", "vid") if v != 0], orientations)
    for e in kinds.get("ElementBeam", []):
        ends = [n for name in ("n1", "n2", "n3") for n in column(e, "elements", name)]
        need("node", ends, nodes)
        need("part", column(e, "elements", "pid"), parts)
    for k, ks in kinds.items():
        for item in ks if k.startswith(("Rigidwall", "BoundarySpcSet", "InitialVelocity")) and k != "InitialVelocityNode" else []:
            sid = getattr(item, "nsid", None)
            if sid is not None and int(sid) != 0:
                need("node set", [int(sid)], sets)
    for k, ks in kinds.items():
        for body in ks if k.startswith("ConstrainedNodalRigidBody") else []:
            # the plain keyword is a table of rigid bodies, the others one each
            rows = body.constrained_nodal_rigid_bodies.to_dict("records") if not hasattr(body, "nsid") \
                else [{f: getattr(body, f, None) for f in ("nsid", "pnode", "nodeid")}]
            for row in rows:
                need("node set", [int(row["nsid"])], sets)
                for field in ("pnode", "nodeid"):
                    value = row.get(field)
                    if value is not None and value == value and int(value) != 0:
                        need("node", [int(value)], nodes)
    for joint in kinds.get("ConstrainedJointTranslational", []):
        need("node", [int(getattr(joint, f"n{i}")) for i in range(1, 7)], nodes)
    for p in kinds.get("Part", []):
        need("section", [int(v) for v in p.parts["secid"].dropna()], sections)
        need("material", [int(v) for v in p.parts["mid"].dropna()], materials)
    for s in kinds.get("SetNodeList", []):
        members = [int(s.nodes[i]) for i in range(len(s.nodes))]
        need("node", [n for n in members if n not in external], nodes)
    for load in kinds.get("LoadNodePoint", []):
        need("node", column(load, "nodes", "nid"), nodes)
        need("curve", column(load, "nodes", "lcid"), set(curves))
    history = []
    for h in kinds.get("DatabaseHistoryNode", []):
        ids = [getattr(h, f"id{i}") for i in range(1, 9)]
        history += [int(v) for v in ids if v is not None and int(v) != 0]
    need("node", history, nodes)
    for k, ms in kinds.items():
        for m in ms if k.startswith("Mat") else []:
            for field in ("lcd", "lcdl", "lcdu"):
                value = getattr(m, field, None)
                if value is not None and int(value) != 0:
                    need("curve", [int(value)], set(curves))
    curve = []
    every = {}
    for c in curves.values():
        every[int(c.lcid)] = [[float(a), float(o)] for a, o in zip(c.curves["a1"], c.curves["o1"])]
        curve = [[float(a), float(o)] for a, o in zip(c.curves["a1"], c.curves["o1"])]
    # every id the deck defines, per LS-DYNA id space (includes packed by
    # their --id-offset must not share one)
    elements = [int(m.eid) for m in kinds.get("ElementMass", [])]
    elements += [i for e in kinds.get("ElementDiscrete", []) for i in column(e, "elements", "eid")]
    ids = {
        "node": sorted(nodes),
        "element": sorted(elements),
        "part": sorted(parts),
        "section": sorted(sections),
        "material": sorted(materials),
        "node set": sorted(sets),
        "curve": sorted(curves),
        "orientation": sorted(orientations),
    }
    result = deck.validate()
    print(json.dumps({
        "keywords": [type(k).__name__ for k in deck.all_keywords],
        "unprocessed": list(loaded._unprocessed_keywords),
        "strings": sum(isinstance(k, str) for k in deck.all_keywords),
        "errors": [str(e) for e in result.errors],
        "undefined": undefined,
        "mass_nodes": masses,
        "history_nodes": history,
        "curve": curve,
        "curves": every,
        "ids": ids,
    }))


main()
