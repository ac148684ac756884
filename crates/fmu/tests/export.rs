//! `stljit_fmu::export`: the archive's entries, the variable mapping of both dialects, the
//! manifest's round trip, and the same bytes for the same input.

use std::io::Read as _;
use stljit_api::Project;
use stljit_fmu::{Causality, ExportOptions, FmiType, Manifest, export};

fn options(locals: &[&str]) -> ExportOptions<'static> {
    ExportOptions {
        model_identifier: "plc".into(),
        scan_ms: 10,
        locals: locals.iter().map(|s| s.to_string()).collect(),
        runtime: b"\x7fELF not really a library",
        platform: "linux64",
        library_extension: "so",
    }
}

fn entries(bytes: &[u8]) -> Vec<(String, Vec<u8>)> {
    let mut zip = zip::ZipArchive::new(std::io::Cursor::new(bytes)).expect("a zip");
    (0..zip.len())
        .map(|i| {
            let mut f = zip.by_index(i).expect("entry");
            let mut data = Vec::new();
            f.read_to_end(&mut data).expect("readable");
            (f.name().expect("a name").to_string(), data)
        })
        .collect()
}

fn traffic() -> Project {
    Project::new()
        .file("../../examples/traffic_light/traffic_light.awl")
        .unwrap()
        .symbols_file("../../examples/traffic_light/symbols.txt")
        .unwrap()
}

#[test]
fn the_archive_holds_the_description_binary_and_resources() {
    let bytes = export(&traffic(), &options(&["T37:i", "VD100:real"])).unwrap();
    let files = entries(&bytes);
    let names: Vec<&str> = files.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(
        names,
        [
            "modelDescription.xml",
            "binaries/linux64/plc.so",
            "resources/stljit.txt",
            "resources/program/traffic_light.awl",
            "resources/program/symbols.txt"
        ]
    );
    let manifest = Manifest::parse(std::str::from_utf8(&files[2].1).unwrap()).unwrap();
    assert_eq!(Manifest::parse(&manifest.to_text()).unwrap(), manifest);
    assert_eq!(
        (manifest.dialect.as_str(), manifest.cpu.as_str()),
        ("s7", "a5")
    );
    let xml = std::str::from_utf8(&files[0].1).unwrap();
    assert!(xml.contains(&format!("guid=\"{}\"", manifest.guid)));
    let by_name = |n: &str| manifest.variables.iter().find(|v| v.name == n).unwrap();
    let ped = by_name("Ped_Button");
    assert_eq!(
        (ped.causality, ped.ty, ped.spec.as_str()),
        (Causality::Input, FmiType::Boolean, "I0.0")
    );
    assert_eq!(by_name("Car_Red").causality, Causality::Output);
    assert_eq!(by_name("VD100:real").ty, FmiType::Real);
    assert_eq!(by_name("T37:i").range, (-32768, 32767));
    let vrs: Vec<u32> = manifest.variables.iter().map(|v| v.vr).collect();
    assert_eq!(vrs, (1..=vrs.len() as u32).collect::<Vec<_>>());
    assert_eq!(
        export(&traffic(), &options(&["T37:i", "VD100:real"])).unwrap(),
        bytes
    );
}

#[test]
fn omron_io_words_and_bits_are_named_by_symbol() {
    let project = Project::new()
        .file("../../examples/omron_conveyor/conveyor.omr")
        .unwrap()
        .symbols_file("../../examples/omron_conveyor/symbols.txt")
        .unwrap();
    let files = entries(&export(&project, &options(&["Batch_Left"])).unwrap());
    let m = Manifest::parse(std::str::from_utf8(&files[2].1).unwrap()).unwrap();
    let list = |c| {
        m.variables
            .iter()
            .filter(|v| v.causality == c)
            .map(|v| v.name.as_str())
            .collect::<Vec<_>>()
    };
    assert_eq!(
        list(Causality::Input),
        [
            "Start_PB",
            "Stop_PB",
            "Product_Sensor",
            "Batch_Reset",
            "Jam_Sensor",
            "Jam_Reset"
        ]
    );
    assert_eq!(
        list(Causality::Output),
        ["Motor", "Horn", "Batch_Done_Lamp", "Jam_Lamp"]
    );
    let batch = m.variables.iter().find(|v| v.name == "Batch_Left").unwrap();
    assert_eq!((batch.ty, batch.range), (FmiType::Integer, (0, 65535)));
}

#[test]
fn bad_input_is_refused_with_the_cause() {
    let bad_id = ExportOptions {
        model_identifier: "9 lives".into(),
        ..options(&[])
    };
    assert!(
        export(&traffic(), &bad_id)
            .unwrap_err()
            .to_string()
            .contains("9 lives")
    );
    let e = export(&traffic(), &options(&["Nope"]))
        .unwrap_err()
        .to_string();
    assert!(e.contains("Nope"), "{e}");
    let broken = Project::new().text("x.stl", "NETWORK 1\nLD I0.0\n= Q99.0\n");
    assert!(
        export(&broken, &options(&[]))
            .unwrap_err()
            .to_string()
            .contains("x.stl:3")
    );
    for (text, line) in [
        ("nonsense\n", 1),
        (
            "stljit-fmu\t1\nguid\t{x}\ndialect\ts7\ncpu\ta5\nscan_ms\t0\nfile\tp.stl\n",
            0,
        ),
        ("stljit-fmu\t1\nvar\t1\tinput\n", 2),
        ("stljit-fmu\t1\nwhat\tever\n", 2),
    ] {
        assert_eq!(Manifest::parse(text).unwrap_err().line, line, "{text}");
    }
}
