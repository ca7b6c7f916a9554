//! The JSON document written as the run goes: its head once the files are read, each
//! result as it is known, its tail (warnings, summary) at the end — the same text as
//! [`render_json`] of the whole report, without keeping every result until the end.

use super::{PropertyReport, RunReport, Summary, render_json};

/// Where the document stands.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Section {
    /// Nothing written yet.
    Unopened,
    /// The head is written, no list is open.
    Head,
    /// Inside the list of `equiv`'s state correspondences.
    Correspondences,
    /// Inside the list of results.
    Properties,
}

/// A JSON report written piece by piece. Every piece comes from `serde_json`'s own
/// pretty printer: the head and tail are cut from the document of the report with empty
/// lists, each result is printed alone and indented to its place.
#[derive(Debug)]
pub struct JsonStream {
    section: Section,
    /// Items written in the open list.
    count: usize,
}

/// The key of the results' list as the pretty printer writes it, empty.
const EMPTY_PROPERTIES: &str = "  \"properties\": []";

/// `report` with no results, no correspondences and `summary`: the frame the head and
/// tail are cut from.
fn frame(report: &RunReport, summary: Summary) -> String {
    let empty = RunReport {
        program: report.program.clone(),
        files: report.files.clone(),
        timers: report.timers,
        properties: Vec::new(),
        correspondences: Vec::new(),
        warnings: report.warnings.clone(),
        summary,
        interrupted: report.interrupted,
        unchecked: report.unchecked.clone(),
        equations: Vec::new(),
    };
    render_json(&empty)
}

impl Default for JsonStream {
    fn default() -> Self {
        JsonStream { section: Section::Unopened, count: 0 }
    }
}

impl JsonStream {
    /// Has anything been written?
    pub fn started(&self) -> bool {
        self.section != Section::Unopened
    }

    /// The head: the fields before the lists (program, files, timer model).
    pub fn head(&mut self, report: &RunReport) -> String {
        if self.started() {
            return String::new();
        }
        self.section = Section::Head;
        let text = frame(report, Summary::default());
        let at = text.find(EMPTY_PROPERTIES).unwrap_or(text.len());
        text[..at].to_string()
    }

    /// Closes the open list, if one is, and opens `next`.
    fn enter(&mut self, next: Section) -> String {
        if self.section == next {
            return String::new();
        }
        let mut out = self.close();
        out.push_str(match next {
            Section::Correspondences => "  \"correspondences\": [",
            _ => "  \"properties\": [",
        });
        self.section = next;
        out
    }

    /// Closes the open list (`]`, on its own line unless it is empty) and the line.
    fn close(&mut self) -> String {
        let out = match self.section {
            Section::Correspondences | Section::Properties if self.count > 0 => "\n  ],\n",
            Section::Correspondences | Section::Properties => "],\n",
            _ => "",
        };
        self.section = Section::Head;
        self.count = 0;
        out.to_string()
    }

    /// One item of `section`, after the head.
    fn item(&mut self, report: &RunReport, section: Section, item: &PropertyReport) -> String {
        let mut out = self.head(report);
        out.push_str(&self.enter(section));
        let text = serde_json::to_string_pretty(item).unwrap_or_else(|e| format!("\"{e}\""));
        out.push_str(if self.count == 0 { "\n    " } else { ",\n    " });
        out.push_str(&text.replace('\n', "\n    "));
        self.count += 1;
        out
    }

    /// A result, in its place.
    pub fn property(&mut self, report: &RunReport, item: &PropertyReport) -> String {
        self.item(report, Section::Properties, item)
    }

    /// A state correspondence of `equiv`, in its place.
    pub fn correspondence(&mut self, report: &RunReport, item: &PropertyReport) -> String {
        self.item(report, Section::Correspondences, item)
    }

    /// The rest of the document: the results' list closed (or written empty), then the
    /// warnings, summary and whether the run was interrupted, from `report`.
    pub fn tail(&mut self, report: &RunReport) -> String {
        let mut out = self.head(report);
        out.push_str(&self.enter(Section::Properties));
        let closing = if self.count > 0 { "\n  ]" } else { "]" };
        out.push_str(closing);
        self.section = Section::Head;
        let text = frame(report, report.summary.clone());
        let at = text.find(EMPTY_PROPERTIES).map_or(text.len(), |a| a + EMPTY_PROPERTIES.len());
        out.push_str(&text[at..]);
        out
    }
}

#[cfg(test)]
mod tests {
    use super::JsonStream;
    use crate::report::{Options, RunReport, render_json};

    /// The document written piece by piece, as the console writes it.
    fn streamed(report: &RunReport) -> String {
        let mut json = JsonStream::default();
        let mut out = json.head(report);
        for c in &report.correspondences {
            out.push_str(&json.correspondence(report, c));
        }
        for p in &report.properties {
            out.push_str(&json.property(report, p));
        }
        out + &json.tail(report)
    }

    #[test]
    fn the_document_written_as_the_run_goes_is_the_whole_reports() {
        let root = env!("CARGO_MANIFEST_DIR");
        let at = |p: &str| format!("{root}/{p}");
        let opts = Options { timeout: std::time::Duration::from_secs(5), ..Options::default() };
        let program = |ld: &str, ii: &str| {
            crate::report::run_program(&at(ld), &[at(ii)], &opts).expect("the run")
        };
        let mut reports = vec![
            // A counterexample, proofs.
            program("examples/water_faulty.ld", "examples/water.ii"),
            // Warnings and an unknown.
            program(
                "tests/data/unknown_programs/quotient_never_done.ld",
                "tests/data/unknown_programs/quotient_never_done.ii",
            ),
            // Correspondences before the results.
            crate::report::equiv::run_equiv_with(
                &at("examples/water.st"),
                &at("examples/water.il"),
                &opts,
                &Default::default(),
                &mut (),
            )
            .expect("the comparison"),
        ];
        assert!(!reports[1].warnings.is_empty() && !reports[2].correspondences.is_empty());
        // No result at all, and an interrupted run with the rest listed.
        let mut empty = reports[0].clone();
        empty.properties.clear();
        let mut cut = reports[0].clone();
        cut.properties.truncate(1);
        cut.interrupted = true;
        cut.unchecked = vec![crate::report::Unchecked {
            name: "P2".into(),
            location: reports[0].properties[1].location.clone().expect("located"),
        }];
        reports.extend([empty, cut]);
        for report in &reports {
            assert_eq!(streamed(report), render_json(report));
        }
    }
}
