//! Unit tests of the stimulus CSV parser: accepted forms and every error with its line:column.

use super::*;
use crate::test_resolver::resolve;
use stljit_core::ProfileId;
use stljit_core::ir::{BitLoc, Loc};
use stljit_core::{Area, Width};

fn parse(text: &str) -> Result<Stimulus, StimulusError> {
    Stimulus::parse(text, ProfileId::A5.profile(), &resolve)
}

fn error_at(text: &str) -> (u32, u32, StimulusErrorKind) {
    let e = parse(text).expect_err("must be rejected");
    (e.line, e.col, e.kind)
}

#[test]
fn parses_scan_rows_with_empty_cells() {
    let s = parse("scan,I0.3,IB1,VW100,VD50\n0,1,,-7,1.5\n\n# comment\n5, 0 ,16#0F,,\n").unwrap();
    assert_eq!(s.time_base(), TimeBase::Scan);
    assert_eq!(s.columns().len(), 4);
    assert_eq!(
        s.columns()[0].address,
        Address::Bit(BitLoc {
            area: Area::I,
            byte: 0,
            bit: 3
        })
    );
    assert_eq!(
        s.columns()[2].address,
        Address::Value {
            loc: Loc {
                area: Area::V,
                offset: 100
            },
            width: Width::Word
        }
    );
    let rows = s.rows();
    assert_eq!(rows.len(), 2);
    assert_eq!(rows[0].at, 0);
    assert_eq!(
        rows[0].cells,
        vec![Some(1), None, Some(0xFFF9), Some(1.5f32.to_bits())]
    );
    assert_eq!(rows[1].at, 5);
    assert_eq!(rows[1].line, 5);
    assert_eq!(rows[1].cells, vec![Some(0), Some(15), None, None]);
}

#[test]
fn millisecond_rows_apply_to_the_first_scan_at_or_after_them() {
    let s = parse("t_ms,I0.0\r\n0,1\r\n15,0\r\n20,1\r\n").unwrap();
    assert_eq!(s.time_base(), TimeBase::Millis);
    let due: Vec<u64> = s.rows().iter().map(|r| s.due_scan(r, 10)).collect();
    assert_eq!(due, vec![0, 2, 2]);
}

#[test]
fn header_errors() {
    assert_eq!(error_at(""), (1, 1, StimulusErrorKind::MissingHeader));
    assert_eq!(
        error_at("time,I0.0\n"),
        (1, 1, StimulusErrorKind::BadTimeColumn("time".into()))
    );
    let (line, col, kind) = error_at("scan,I0.0, XY7\n");
    assert_eq!((line, col), (1, 12));
    assert!(matches!(kind, StimulusErrorKind::UnknownAddress { name, .. } if name == "XY7"));
    let (line, col, kind) = error_at("# leading comment\nscan,I0.0,SM0.1\n");
    assert_eq!((line, col), (2, 11));
    assert!(matches!(kind, StimulusErrorKind::NotWritable { name, .. } if name == "SM0.1"));
    assert!(matches!(
        error_at("scan,SMB29\n").2,
        StimulusErrorKind::NotWritable { .. }
    ));
    assert!(parse("scan,SMB30\n").is_ok());
    assert!(matches!(
        error_at("scan,HC0\n").2,
        StimulusErrorKind::NotWritable { .. }
    ));
    assert_eq!(
        error_at("scan,I0.0,I0.0\n"),
        (1, 11, StimulusErrorKind::DuplicateColumn("I0.0".into()))
    );
}

#[test]
fn row_errors_name_line_and_column() {
    let (line, col, kind) = error_at("scan,I0.0,VW0\n0,2,5\n");
    assert_eq!((line, col), (2, 3));
    assert!(
        matches!(kind, StimulusErrorKind::BadValue { column, error: ValueError::OutOfRange { .. }, .. } if column == "I0.0")
    );
    let (line, col, kind) = error_at("scan,I0.0,VW0\n0,1,70000\n");
    assert_eq!((line, col), (2, 5));
    assert!(matches!(kind, StimulusErrorKind::BadValue { .. }));
    let (line, col, kind) = error_at("scan,IB0\n0,-1\n");
    assert_eq!((line, col), (2, 3));
    assert!(matches!(kind, StimulusErrorKind::BadValue { .. }));
    let (line, col, kind) = error_at("scan,VW0\n0,1.5\n");
    assert_eq!((line, col), (2, 3));
    assert!(matches!(
        kind,
        StimulusErrorKind::BadValue {
            error: ValueError::RealNotAllowed { .. },
            ..
        }
    ));
    assert_eq!(
        error_at("scan,I0.0\n0,1,1\n"),
        (
            2,
            5,
            StimulusErrorKind::CellCount {
                expected: 2,
                found: 3
            }
        )
    );
    assert_eq!(
        error_at("scan,I0.0,I0.1\n0,1\n"),
        (
            2,
            4,
            StimulusErrorKind::CellCount {
                expected: 3,
                found: 2
            }
        )
    );
    assert_eq!(
        error_at("scan,I0.0\n-1,1\n"),
        (2, 1, StimulusErrorKind::BadTime("-1".into()))
    );
    assert_eq!(
        error_at("scan,I0.0\n3,1\n2,0\n"),
        (3, 1, StimulusErrorKind::Unsorted { at: 2, previous: 3 })
    );
    assert_eq!(
        error_at("scan,I0.0\n3,1\n  3,0\n"),
        (3, 3, StimulusErrorKind::Unsorted { at: 3, previous: 3 })
    );
    let e = parse("scan,I0.0\n0,7\n").unwrap_err();
    assert_eq!(
        e.to_string(),
        "line 2, column 3: bad value `7` for `I0.0`: a bit must be 0 or 1"
    );
}

#[test]
fn programmatic_rows_are_checked_too() {
    let mut s = Stimulus::empty(TimeBase::Scan, ProfileId::A5.profile());
    assert_eq!(s.add_column("IB0", &resolve), Ok(0));
    assert_eq!(s.add_column("I0.1", &resolve), Ok(1));
    assert!(matches!(
        s.add_column("SMB0", &resolve),
        Err(StimulusErrorKind::NotWritable { .. })
    ));
    s.push_row(0, vec![Some(255), Some(1)]).unwrap();
    let e = s.push_row(1, vec![Some(256), None]).unwrap_err();
    assert_eq!((e.line, e.col), (3, 2));
    let e = s.push_row(1, vec![None, Some(2)]).unwrap_err();
    assert_eq!((e.line, e.col), (3, 3));
    let e = s.push_row(0, vec![None, None]).unwrap_err();
    assert!(matches!(e.kind, StimulusErrorKind::Unsorted { .. }));
    let e = s.push_row(2, vec![None]).unwrap_err();
    assert!(matches!(e.kind, StimulusErrorKind::CellCount { .. }));
}
