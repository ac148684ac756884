//! Unit tests of the stimulus CSV parser: accepted forms and every error with its line:column.

use super::*;
use crate::test_resolver::resolve;
use stljit_core::ProfileId;
use stljit_core::ir::{BitLoc, Loc};
use stljit_core::{Area, Width};

fn parse(text: &str) -> Result<Stimulus, StimulusError> {
    Stimulus::parse(text, ProfileId::A5.profile(), &resolve)
}

/// Address cells of raw values.
fn values(v: &[Option<u32>]) -> Vec<Option<Cell>> {
    v.iter().map(|v| v.map(Cell::Value)).collect()
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
        s.columns()[0].target,
        Target::Address(Address::Bit(BitLoc {
            area: Area::I,
            byte: 0,
            bit: 3
        }))
    );
    assert_eq!(
        s.columns()[2].target,
        Target::Address(Address::Value {
            loc: Loc {
                area: Area::V,
                offset: 100
            },
            width: Width::Word
        })
    );
    let rows = s.rows();
    assert_eq!(rows.len(), 2);
    assert_eq!(rows[0].at, 0);
    assert_eq!(
        rows[0].cells,
        values(&[Some(1), None, Some(0xFFF9), Some(1.5f32.to_bits())])
    );
    assert_eq!(rows[1].at, 5);
    assert_eq!(rows[1].line, 5);
    assert_eq!(rows[1].cells, values(&[Some(0), Some(15), None, None]));
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

fn parse_for(profile: ProfileId, text: &str) -> Result<Stimulus, StimulusError> {
    Stimulus::parse(text, profile.profile(), &resolve)
}

/// `HSCn` and `PORTn` are reserved in any case. The a5 has HC0 and HC1 (s7-200-more §8.2:
/// "a5: HC0 and HC1 exist", = HSC0/HSC1 of the s7-200 table) and both ports (§10, every S7
/// profile). Steps are held (§11.2 `hsc_steps`, held until set again), bytes are not.
#[test]
fn hsc_and_port_columns() {
    let s = parse(
        "scan,I0.0,hsc0,HSC1,Port0,PORT1\n0,1,10,,16#48454C4C4F0D,\n4,,-3,16#FFFFFFFF,,16#00\n",
    )
    .unwrap();
    let targets: Vec<Target> = s.columns().iter().map(|c| c.target).collect();
    assert_eq!(
        &targets[1..],
        &[
            Target::HscSteps(0),
            Target::HscSteps(1),
            Target::Receive(0),
            Target::Receive(1)
        ]
    );
    assert_eq!(s.columns()[1].name, "hsc0", "the name as written");
    assert!(targets[1].is_held() && targets[0].is_held() && !targets[3].is_held());
    // "HELLO\r" in ASCII: H 16#48, E 16#45, L 16#4C, L, O 16#4F, CR 16#0D.
    assert_eq!(
        s.rows()[0].cells,
        vec![
            Some(Cell::Value(1)),
            Some(Cell::Steps(10)),
            None,
            Some(Cell::Bytes(b"HELLO\r".to_vec())),
            None
        ]
    );
    // 16#FFFFFFFF is the 32-bit pattern of -1 (a DINT constant); 16#00 is one byte, 0.
    assert_eq!(
        s.rows()[1].cells,
        vec![
            None,
            Some(Cell::Steps(-3)),
            Some(Cell::Steps(-1)),
            None,
            Some(Cell::Bytes(vec![0]))
        ]
    );
    // HSC2..HSC5 and a sixth port exist nowhere on the a5; the s7-200 has HSC0..HSC5 (§8.2).
    assert!(parse_for(ProfileId::S7_200, "scan,HSC5\n0,1\n").is_ok());
    assert!(parse_for(ProfileId::Smart, "scan,HSC3,PORT1\n0,1,16#01\n").is_ok());
}

#[test]
fn steps_cells() {
    // i32's range: -2^31 … 2^31 - 1 in decimal; 16#/2# give the 32-bit pattern.
    assert_eq!(parse_steps("0"), Ok(0));
    assert_eq!(parse_steps(" +25 "), Ok(25));
    assert_eq!(parse_steps("-2147483648"), Ok(i32::MIN));
    assert_eq!(parse_steps("16#7FFFFFFF"), Ok(i32::MAX));
    assert_eq!(parse_steps("16#80000000"), Ok(i32::MIN));
    assert_eq!(parse_steps("2#101"), Ok(5));
    for bad in [
        "2147483648",
        "1.5",
        "ten",
        "16#",
        "16#100000000",
        "16#-1",
        "#10",
    ] {
        assert_eq!(parse_steps(bad), Err(CellError::Steps), "{bad}");
    }
}

#[test]
fn byte_cells() {
    assert_eq!(parse_bytes("16#4f4B0d"), Ok(vec![0x4F, 0x4B, 0x0D]));
    assert_eq!(parse_bytes("16#"), Err(CellError::NoBytes));
    assert_eq!(parse_bytes("16#4F4"), Err(CellError::OddDigits(3)));
    assert_eq!(parse_bytes("4F4B"), Err(CellError::BytesSyntax));
    assert_eq!(parse_bytes("16#4G"), Err(CellError::BytesSyntax));
    assert_eq!(parse_bytes("16#4F 4B"), Err(CellError::BytesSyntax));
    assert_eq!(parse_bytes("79"), Err(CellError::BytesSyntax));
}

#[test]
fn hsc_and_port_errors_name_line_and_column() {
    // The a5 has HSC0 and HSC1 only (§8.2).
    let (line, col, kind) = error_at("scan,I0.0,HSC2\n");
    assert_eq!((line, col), (1, 11));
    assert_eq!(
        kind,
        StimulusErrorKind::NoCounter {
            name: "HSC2".into(),
            cpu: "A5",
            have: "HSC0, HSC1".into()
        }
    );
    assert!(matches!(
        parse_for(ProfileId::Smart, "scan,HSC4\n").unwrap_err().kind,
        StimulusErrorKind::NoCounter { .. }
    ));
    assert!(matches!(
        error_at("scan,HSC99999999999\n").2,
        StimulusErrorKind::NoCounter { .. }
    ));
    assert!(matches!(
        error_at("scan,PORT2\n").2,
        StimulusErrorKind::NoPort { .. }
    ));
    // The Omron CP profiles have neither (core::hsc: no counters; §10 is S7 only).
    let e = parse_for(ProfileId::Cp1h, "t_ms,PORT0\n").unwrap_err();
    assert_eq!((e.line, e.col), (1, 6));
    assert_eq!(
        e.to_string(),
        "line 1, column 6: `PORT0`: the CP1H has no such serial port (it has: none)"
    );
    assert!(matches!(
        parse_for(ProfileId::Cp1h, "scan,HSC0\n").unwrap_err().kind,
        StimulusErrorKind::NoCounter { have, .. } if have == "none"
    ));
    assert_eq!(
        error_at("scan,HSC0,hsc0\n"),
        (1, 11, StimulusErrorKind::DuplicateColumn("hsc0".into()))
    );
    // Cells: `HELLO` is 10 hex digits; one more is 11, five bytes and a half.
    let e = parse("scan,I0.0,PORT0\n0,1,16#48454C4C4F0\n").unwrap_err();
    assert_eq!((e.line, e.col), (2, 5));
    assert_eq!(
        e.to_string(),
        "line 2, column 5: bad cell `16#48454C4C4F0` for `PORT0`: 11 hex digits: every byte is \
         two (16#4F4B0D is 3 bytes)"
    );
    let (line, col, kind) = error_at("scan,HSC1\n0,1\n3, 2.5\n");
    assert_eq!((line, col), (3, 4));
    assert!(matches!(
        kind,
        StimulusErrorKind::BadCell {
            error: CellError::Steps,
            ..
        }
    ));
    // A name that only starts like a reserved one is an address or symbol as before.
    assert!(matches!(
        error_at("scan,HSC\n").2,
        StimulusErrorKind::UnknownAddress { .. }
    ));
    assert!(matches!(
        error_at("scan,PORT0A\n").2,
        StimulusErrorKind::UnknownAddress { .. }
    ));
}

#[test]
fn programmatic_hsc_and_port_cells() {
    let mut s = Stimulus::empty(TimeBase::Scan, ProfileId::A5.profile());
    assert_eq!(s.add_column("HSC0", &resolve), Ok(0));
    assert_eq!(s.add_column("PORT0", &resolve), Ok(1));
    assert_eq!(s.add_column("VW0", &resolve), Ok(2));
    // A steps cell pushed as raw bits is the i32's pattern.
    s.push_row(0, vec![Some(u32::MAX), None, Some(7)]).unwrap();
    assert_eq!(
        s.rows()[0].cells,
        vec![Some(Cell::Steps(-1)), None, Some(Cell::Value(7))]
    );
    let e = s.push_row(1, vec![None, Some(79), None]).unwrap_err();
    assert_eq!((e.line, e.col), (3, 3));
    assert!(matches!(
        e.kind,
        StimulusErrorKind::BadCell {
            error: CellError::Kind("received bytes"),
            ..
        }
    ));
    s.push_cells(1, vec![None, Some(Cell::Bytes(b"OK".to_vec())), None])
        .unwrap();
    let e = s
        .push_cells(2, vec![None, Some(Cell::Bytes(Vec::new())), None])
        .unwrap_err();
    assert!(matches!(
        e.kind,
        StimulusErrorKind::BadCell {
            error: CellError::NoBytes,
            ..
        }
    ));
    let e = s
        .push_cells(2, vec![None, None, Some(Cell::Steps(1))])
        .unwrap_err();
    assert!(matches!(
        e.kind,
        StimulusErrorKind::BadCell {
            error: CellError::Kind("a value"),
            ..
        }
    ));
    let e = s
        .push_cells(2, vec![None, None, Some(Cell::Value(65536))])
        .unwrap_err();
    assert!(matches!(e.kind, StimulusErrorKind::BadValue { .. }));
    assert_eq!(s.rows().len(), 2);
}
