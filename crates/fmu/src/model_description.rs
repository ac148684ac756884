//! `modelDescription.xml` for FMI 2.0 co-simulation, written with quick-xml.
//!
//! Every variable is `discrete` (a PLC's values change only at scans). Inputs have a start
//! value (0 or false, the cold-start image) and no `initial`; outputs and locals are
//! `initial="calculated"` without a start. Every output is listed under `ModelStructure/Outputs`
//! and `InitialUnknowns` (FMI 2.0 §2.2.8) with no `dependencies` attribute (it may depend on any
//! input). The default experiment's step is the scan time.

use crate::variables::{Causality, FmiType, Variable};
use quick_xml::Writer;
use quick_xml::events::{BytesDecl, Event};
use std::io;

/// What goes into the description besides the variables.
#[derive(Clone, Debug)]
pub struct Description<'a> {
    /// `modelName` (the program's first file stem).
    pub model_name: &'a str,
    /// `modelIdentifier`: the binary's file name stem, a C identifier.
    pub model_identifier: &'a str,
    /// `guid`, braces included.
    pub guid: &'a str,
    /// A one-line description of the model.
    pub description: &'a str,
    /// The scan time, the default experiment's step.
    pub scan_ms: u64,
    /// `generationTool`.
    pub tool: &'a str,
}

/// The XML text.
pub fn write(d: &Description<'_>, variables: &[Variable]) -> io::Result<String> {
    let mut w = Writer::new_with_indent(Vec::new(), b' ', 2);
    w.write_event(Event::Decl(BytesDecl::new("1.0", Some("UTF-8"), None)))?;
    let step = format!("{}", d.scan_ms as f64 / 1000.0);
    w.create_element("fmiModelDescription")
        .with_attributes([
            ("fmiVersion", "2.0"),
            ("modelName", d.model_name),
            ("guid", d.guid),
            ("description", d.description),
            ("generationTool", d.tool),
            ("variableNamingConvention", "flat"),
            ("numberOfEventIndicators", "0"),
        ])
        .write_inner_content(|w| {
            w.create_element("CoSimulation")
                .with_attributes([
                    ("modelIdentifier", d.model_identifier),
                    ("canHandleVariableCommunicationStepSize", "true"),
                    ("canInterpolateInputs", "false"),
                    ("canGetAndSetFMUstate", "true"),
                    ("canSerializeFMUstate", "true"),
                    ("canNotUseMemoryManagementFunctions", "true"),
                ])
                .write_empty()?;
            w.create_element("DefaultExperiment")
                .with_attributes([("startTime", "0.0"), ("stepSize", step.as_str())])
                .write_empty()?;
            w.create_element("ModelVariables")
                .write_inner_content(|w| {
                    for v in variables {
                        scalar_variable(w, v)?;
                    }
                    Ok(())
                })?;
            w.create_element("ModelStructure")
                .write_inner_content(|w| {
                    let outputs: Vec<String> = variables
                        .iter()
                        .enumerate()
                        .filter(|(_, v)| v.causality == Causality::Output)
                        .map(|(i, _)| (i + 1).to_string())
                        .collect();
                    if outputs.is_empty() {
                        return Ok(());
                    }
                    for list in ["Outputs", "InitialUnknowns"] {
                        w.create_element(list).write_inner_content(|w| {
                            for index in &outputs {
                                w.create_element("Unknown")
                                    .with_attribute(("index", index.as_str()))
                                    .write_empty()?;
                            }
                            Ok(())
                        })?;
                    }
                    Ok(())
                })?;
            Ok(())
        })?;
    String::from_utf8(w.into_inner()).map_err(|e| io::Error::new(io::ErrorKind::InvalidData, e))
}

fn scalar_variable(w: &mut Writer<Vec<u8>>, v: &Variable) -> io::Result<()> {
    let vr = v.vr.to_string();
    let mut attrs = vec![
        ("name", v.name.as_str()),
        ("valueReference", vr.as_str()),
        ("description", v.description.as_str()),
        ("causality", v.causality.name()),
        ("variability", "discrete"),
    ];
    if v.causality != Causality::Input {
        attrs.push(("initial", "calculated"));
    }
    let (min, max) = (v.range.0.to_string(), v.range.1.to_string());
    w.create_element("ScalarVariable")
        .with_attributes(attrs)
        .write_inner_content(|w| {
            let mut el = w.create_element(v.ty.name());
            if v.causality == Causality::Input {
                el = el.with_attribute((
                    "start",
                    match v.ty {
                        FmiType::Real => "0.0",
                        FmiType::Integer => "0",
                        FmiType::Boolean => "false",
                    },
                ));
            }
            if v.ty == FmiType::Integer {
                el = el.with_attributes([("min", min.as_str()), ("max", max.as_str())]);
            }
            el.write_empty()?;
            Ok(())
        })?;
    Ok(())
}
