//! An FMU instance driven through its safe Rust methods (the C functions only translate
//! pointers around them): the state machine, steps mapped onto scans, inputs, outputs, saved
//! states, and the resource-location URIs masters pass.

use std::path::PathBuf;
use stljit_api::{Project, Value};
use stljit_fmu::{ExportOptions, FmiType, Manifest, export};
use stljit_fmu_runtime::{Instance, Problem, State, resource_dir};

/// Writes the resources of the level controller's FMU into a fresh directory.
fn resources(name: &str) -> (PathBuf, Manifest) {
    let dir = std::env::temp_dir().join(format!("stljit-fmu-test-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let project = Project::new().text(
        "level.stl",
        "NETWORK 1\nLDW< AIW0, 100\nS Q0.0, 1\nNETWORK 2\nLDW> AIW0, 200\nR Q0.0, 1\n\
         NETWORK 3\nLD SM0.0\nINCW VW0\n",
    );
    let opts = ExportOptions {
        model_identifier: "level".into(),
        scan_ms: 10,
        locals: vec!["VW0".into()],
        runtime: b"",
        platform: "linux64",
        library_extension: "so",
    };
    let bytes = export(&project, &opts).unwrap();
    let mut zip = zip::ZipArchive::new(std::io::Cursor::new(bytes)).unwrap();
    zip.extract(&dir).unwrap();
    let text = std::fs::read_to_string(dir.join("resources/stljit.txt")).unwrap();
    (dir.join("resources"), Manifest::parse(&text).unwrap())
}

fn vr(m: &Manifest, name: &str) -> u32 {
    m.variables.iter().find(|v| v.name == name).unwrap().vr
}

#[test]
fn steps_run_the_scans_that_start_in_them() {
    let (dir, m) = resources("steps");
    let mut inst = Instance::new(&dir, &m.guid).unwrap();
    let (level, valve, count) = (vr(&m, "AIW0"), vr(&m, "Q0.0"), vr(&m, "VW0"));
    assert!(
        inst.do_step(0.0, 0.1).is_err(),
        "no step before initialization"
    );
    inst.setup(0.0).unwrap();
    inst.set(level, FmiType::Integer, Value::Int(50)).unwrap();
    assert_eq!(inst.get(level, FmiType::Integer), Ok(Value::Int(50)));
    inst.enter_initialization().unwrap();
    inst.exit_initialization().unwrap();
    inst.do_step(0.0, 0.015).unwrap(); // scans at 0 and 10 ms
    assert_eq!(inst.get(count, FmiType::Integer), Ok(Value::Int(2)));
    assert_eq!(inst.get(valve, FmiType::Boolean), Ok(Value::Bool(true)));
    inst.do_step(0.015, 0.004).unwrap(); // [15, 19) ms: no scan starts
    assert_eq!(inst.get(count, FmiType::Integer), Ok(Value::Int(2)));
    let saved = inst.save();
    inst.set(level, FmiType::Integer, Value::Int(300)).unwrap();
    inst.do_step(0.019, 0.1).unwrap(); // 20 ... 110 ms
    assert_eq!(inst.get(count, FmiType::Integer), Ok(Value::Int(12)));
    assert_eq!(inst.get(valve, FmiType::Boolean), Ok(Value::Bool(false)));
    let bytes = saved.to_bytes();
    inst.restore(&stljit_fmu_runtime::FmuState::from_bytes(&bytes).unwrap())
        .unwrap();
    assert!((inst.time() - 0.019).abs() < 1e-12);
    assert_eq!(inst.get(count, FmiType::Integer), Ok(Value::Int(2)));
    // Refusals name the cause.
    let refuse = |r: Result<(), Problem>, what: &str| match r {
        Err(Problem::Error(m)) => assert!(m.contains(what), "{m}"),
        other => panic!("expected an error with {what}, got {other:?}"),
    };
    refuse(
        inst.set(valve, FmiType::Boolean, Value::Bool(true)),
        "only inputs",
    );
    refuse(
        inst.set(level, FmiType::Real, Value::Real(1.0)),
        "is Integer, not Real",
    );
    refuse(
        inst.set(99, FmiType::Integer, Value::Int(1)),
        "value reference 99",
    );
    refuse(
        inst.set(level, FmiType::Integer, Value::Int(70000)),
        "70000",
    );
    refuse(inst.do_step(0.5, 0.1), "the FMU is at t = 0.019");
    refuse(inst.do_step(0.019, -1.0), "finite forward step");
    assert!(stljit_fmu_runtime::FmuState::from_bytes(&bytes[..5]).is_err());
    inst.terminate().unwrap();
    assert_eq!(inst.state(), State::Terminated);
    refuse(
        inst.set(level, FmiType::Integer, Value::Int(1)),
        "after fmi2Terminate",
    );
    inst.reset();
    assert_eq!(
        (inst.state(), inst.plc().scan_no()),
        (State::Instantiated, 0)
    );
}

#[test]
fn a_wrong_guid_or_missing_resources_are_refused() {
    let (dir, _) = resources("guid");
    match Instance::new(&dir, "{not-it}") {
        Err(Problem::Error(m)) => assert!(m.contains("GUID mismatch"), "{m}"),
        other => panic!("{other:?}"),
    }
    assert!(Instance::new(&dir.join("nowhere"), "{x}").is_err());
}

#[test]
fn resource_locations_are_file_uris() {
    assert_eq!(
        resource_dir("file:///tmp/a%20b/resources"),
        Ok(PathBuf::from("/tmp/a b/resources"))
    );
    assert_eq!(resource_dir("file:/tmp/r"), Ok(PathBuf::from("/tmp/r")));
    assert_eq!(
        resource_dir("file://localhost/tmp/r"),
        Ok(PathBuf::from("/tmp/r"))
    );
    assert_eq!(
        resource_dir("file:///C:/fmu/resources"),
        Ok(PathBuf::from("C:/fmu/resources"))
    );
    assert!(resource_dir("http://example.com/r").is_err());
}
