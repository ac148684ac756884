//! The Omron generator's programs are valid (the front end accepts every one of them) and,
//! together, use every instruction form and operand form the front end accepts.

use super::*;

fn failures(cases: impl Iterator<Item = (String, Result<OmronCase, GenError>)>) -> Vec<String> {
    cases
        .filter_map(|(name, r)| r.err().map(|e| format!("{name}: {e}\n{}", e.source)))
        .collect()
}

#[test]
fn generated_programs_compile() {
    let cfg = GenConfig::default();
    let bad = failures((0..3000).map(|seed| {
        let mut c = Choices::from_seed(seed);
        (format!("seed {seed}"), generate(&mut c, &cfg))
    }));
    assert!(
        bad.is_empty(),
        "{} of 3000 rejected; first:\n{}",
        bad.len(),
        bad[0]
    );
}

#[test]
fn programs_from_fuzzer_bytes_compile() {
    let bad = failures((0..1000).map(|i| {
        let mut r = crate::rng::SplitMix64::new(i);
        let bytes: Vec<u8> = (0..(i % 500)).map(|_| r.next_u64() as u8).collect();
        let mut c = Choices::from_bytes(&bytes);
        (
            format!("bytes #{i}"),
            generate(&mut c, &GenConfig::default()),
        )
    }));
    assert!(
        bad.is_empty(),
        "{} of 1000 rejected; first:\n{}",
        bad.len(),
        bad[0]
    );
}

/// Every instruction form (each mnemonic of the front end's table, STEP, SNXT, BPRG and BEND
/// among them, and every arithmetic and comparison instruction, alone and with each option it
/// takes), every operand form and every program form (the `$TASK`/`$FB` units, several tasks,
/// a step area inside IL, a block program inside a step area, a backward jump, both options)
/// appears in the coverage of a fixed-seed batch of 2,000 programs.
#[test]
fn every_omron_form_is_generated() {
    let mut cov = crate::coverage::Coverage::default();
    for seed in 0..2000 {
        let mut c = Choices::from_seed(seed);
        if let Ok(g) = generate(&mut c, &GenConfig::default()) {
            cov.add_omron_source(&g.source, g.options);
        }
    }
    let missing = cov.missing_omron();
    assert!(missing.is_empty(), "never generated: {missing:?}");
    // Not just once: the rarest required form still comes up several times.
    let rarest = stljit_front_omron::forms::mnemonic_forms()
        .into_iter()
        .map(|m| (cov.omron_mnemonics[&m], m))
        .min();
    assert!(rarest.as_ref().is_some_and(|r| r.0 >= 5), "{rarest:?}");
    let rarest_program = stljit_front_omron::forms::PROGRAM_FORMS
        .iter()
        .map(|f| (cov.omron_programs[f], *f))
        .min();
    assert!(
        rarest_program.is_some_and(|r| r.0 >= 5),
        "{rarest_program:?}"
    );
    // The new instructions are among the table's, so required above; not just once either.
    for m in ["STEP", "SNXT", "BPRG", "BEND", "!LD", "!OUT", "!MOV"] {
        assert!(
            cov.omron_mnemonics[m] >= 20,
            "{m}: {}",
            cov.omron_mnemonics[m]
        );
    }
}
