//! scratch
use bumpsim_ident::estimate::identify;
use bumpsim_ident::study::Study;
fn main() {
    let study = Study::read(std::path::Path::new("examples/nhtsa-10146/study.toml")).unwrap();
    for dof in study.dofs() {
        let cases = study.cases(dof).unwrap();
        let c = &cases[0];
        println!(
            "case: {} samples, window {:?}, step {}, start {}",
            c.force.len(),
            c.window,
            c.step,
            c.start
        );
        let r = identify(&cases, &study.settings(dof).unwrap(), &|| {}).unwrap();
        println!("{}", bumpsim_ident::report::parameter_table(&r));
        println!("{}", bumpsim_ident::report::case_lines(&r));
        println!("{:?} {:?} {:?}", r.starts, r.warnings, r.stop);
    }
}
