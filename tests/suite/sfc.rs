//! Sequential function charts in Structured Text files and PLCopen `<SFC>` bodies: random charts (`common/sfc_gen.rs`, as text and as XML) compile to equations that hold at every scan of the scan model's simulator, and malformed or unsupported charts are refused with located errors (`tests/data/sfc/rejects/`; for PLCopen, `tests/data/plcopen/refused/chart_*`). What the charts mean is checked against matiec by `tests/suite/iec_oracle.rs` (`random_sfc`).

use crate::common;
use crate::common::scan_eval;
use crate::common::sfc_gen;
use crate::common::st_gen;

use ii_prove::diag::Sources;
use scan_eval::{Checked, Tally, check_scans};

/// The PLCopen project `text`, whose program is a chart, lowered and compiled.
fn compile_xml(
    text: &str,
) -> Result<(ii_prove::program::Program, ii_prove::ladder::CompiledProgram), String> {
    use ii_prove::ladder::plcopen;
    let mut sources = Sources::new();
    let file = sources.add("chart.xml", text.to_string());
    let project = plcopen::read_plcopen(&sources, file).map_err(|e| format!("{e:?}"))?;
    let lowered = plcopen::st_program(&mut sources, &project, &plcopen::Selection::default())
        .ok_or("no chart")?
        .map_err(|e| format!("{e:?}"))?;
    let compiled = ii_prove::program::compile(&lowered.program, &Default::default())
        .map_err(|e| format!("{e:?}"))?;
    Ok((lowered.program, compiled))
}

/// Random charts (`II_SFC_PROGRAMS`, 150 by default), as Structured Text and as PLCopen
/// `<SFC>` bodies: every compiled equation and recurrence holds at every scan of the
/// scan model's simulator, and every bit is known.
#[test]
fn random_charts_agree_with_the_scan_simulator() {
    let n: u64 = std::env::var("II_SFC_PROGRAMS").ok().and_then(|v| v.parse().ok()).unwrap_or(150);
    let mut programs = 0u64;
    let mut tally = Tally::default();
    for seed in 0..2 * n {
        let xml = seed % 2 == 1;
        let g = if xml { sfc_gen::project(seed / 2) } else { sfc_gen::program(seed / 2) };
        let compiled =
            if xml { compile_xml(&g.text) } else { common::compile_text("chart.st", &g.text) };
        let (program, compiled) = match compiled {
            Ok(x) => x,
            Err(e) => {
                tally.fail(seed, &g.text, &format!("refused: {e}"));
                continue;
            }
        };
        programs += 1;
        let schedule = st_gen::schedule_of(&g.inputs, seed / 2, 100);
        let run = check_scans(&program, &compiled, g.cycle_us, &schedule, &mut |_, _| Ok(()));
        tally.add(seed, &g.text, run);
    }
    let Checked { scans, hypotheses, .. } = tally.totals;
    tally.finish(&format!(
        "random charts: {programs} compiled, {scans} scans, {hypotheses} hypotheses checked at every scan"
    ));
}

/// Every file of `tests/data/sfc/rejects/` is refused with a located error.
#[test]
fn malformed_and_unsupported_charts_are_refused_with_located_errors() {
    assert!(common::check_rejects("tests/data/sfc/rejects", "st") >= 6);
}
