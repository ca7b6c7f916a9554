//! The HTML report read back as XML: a summary row per property with the verdicts of the JSON report of the same program, the refuted property's diagram with a track per signal of its counterexample, every link resolving, `--html FILE` beside another format, escaping, and unwritable paths.

use std::collections::BTreeSet;
use std::path::PathBuf;
use std::process::{Command, Output};

fn ii_prove(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_ii-prove"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("the binary runs")
}

fn text(out: &[u8]) -> String {
    String::from_utf8_lossy(out).into_owned()
}

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("ii-prove-html-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

const FAULTY: [&str; 2] = ["examples/water_faulty.ld", "examples/water.ii"];

/// The page as XML (its `<!DOCTYPE html>` is a DTD to the parser).
fn parse(page: &str) -> roxmltree::Document<'_> {
    let opts = roxmltree::ParsingOptions { allow_dtd: true, ..Default::default() };
    roxmltree::Document::parse_with_options(page, opts).unwrap_or_else(|e| panic!("{e}"))
}

/// Every `href="#…"` of the page names an element's `id`.
fn links_resolve(doc: &roxmltree::Document) -> usize {
    let ids: BTreeSet<&str> = doc.descendants().filter_map(|n| n.attribute("id")).collect();
    let mut links = 0;
    for a in doc.descendants().filter(|n| n.has_tag_name("a")) {
        let href = a.attribute("href").expect("a link has a target");
        let target = href.strip_prefix('#').expect("links stay in the page");
        assert!(ids.contains(target), "no element has the id {target}");
        links += 1;
    }
    links
}

#[test]
fn the_faulty_plant_report_shows_every_verdict_the_diagram_and_the_proofs() {
    let out = ii_prove(&[FAULTY[0], FAULTY[1], "--format", "html"]);
    assert_eq!(out.status.code(), Some(1), "{}", text(&out.stderr));
    let page = text(&out.stdout);
    let doc = parse(&page);
    assert!(page.starts_with("<!DOCTYPE html>"));
    assert!(!page.contains("<script") && !page.contains("<link"), "no script, no external style");
    let json: serde_json::Value =
        serde_json::from_slice(&ii_prove(&[FAULTY[0], FAULTY[1], "--format", "json"]).stdout)
            .expect("JSON");
    let props = json["properties"].as_array().unwrap();
    // The summary: one row per property, with its verdict.
    let rows: Vec<_> = doc
        .descendants()
        .find(|n| n.attribute("id") == Some("summary"))
        .expect("a summary table")
        .descendants()
        .filter(|n| n.has_tag_name("tr") && n.attribute("data-verdict").is_some())
        .collect();
    assert_eq!(rows.len(), props.len());
    for (row, p) in rows.iter().zip(props) {
        let name = row.descendants().find(|n| n.has_tag_name("a")).and_then(|a| a.text());
        assert_eq!(name, p["name"].as_str());
        assert_eq!(row.attribute("data-verdict"), p["status"].as_str());
    }
    // Each refuted property: a diagram with a track per signal of its counterexample,
    // the violation marked.
    let refuted: Vec<&serde_json::Value> =
        props.iter().filter(|p| p["status"] == "refuted").collect();
    assert!(!refuted.is_empty());
    for p in refuted {
        let id = format!("p-{}", p["name"].as_str().unwrap());
        let section = doc.descendants().find(|n| n.attribute("id") == Some(&id)).expect("section");
        let svg = section.descendants().find(|n| n.has_tag_name("svg")).expect("a diagram");
        let tracks: BTreeSet<&str> = svg
            .descendants()
            .filter(|n| n.attribute("class") == Some("track"))
            .filter_map(|n| n.attribute("data-signal"))
            .collect();
        // The tracks are the text diagram's rows (its labels before the block glyphs).
        let rows: BTreeSet<String> = p["counterexample"]["diagram"]
            .as_array()
            .unwrap()
            .iter()
            .filter_map(|l| l.as_str())
            .filter_map(|l| {
                let at = l.find(|c: char| ('\u{2580}'..='\u{259f}').contains(&c))?;
                Some(l[..at].trim_end().to_string())
            })
            .filter(|label| !label.is_empty())
            .collect();
        assert!(rows.len() >= 3, "{rows:?}");
        assert_eq!(rows, tracks.iter().map(|t| t.to_string()).collect(), "tracks");
        assert!(svg.descendants().any(|n| n.attribute("class") == Some("mark")));
        let time = p["counterexample"]["time"].as_str().unwrap();
        assert!(
            section
                .descendants()
                .any(|n| n.text().is_some_and(|t| t.contains(&format!("t = {time} s")))),
            "the violation's instant is said"
        );
    }
    // The proved ones show their proofs, and cite equations of the appendix.
    let proved = props.iter().filter(|p| p["status"] == "proved").count();
    let traces = doc.descendants().filter(|n| n.attribute("class") == Some("trace")).count();
    assert_eq!(traces, proved);
    let cited = doc
        .descendants()
        .filter(|n| n.has_tag_name("a"))
        .filter(|a| a.attribute("href").is_some_and(|h| h.starts_with("#eq-")))
        .count();
    assert!(cited > 0, "no proof cites the program");
    assert!(links_resolve(&doc) > props.len());
    // The appendix: the program's equations, each with its rung.
    let shown = text(&ii_prove(&["show", FAULTY[0]]).stdout);
    let equations: Vec<_> = doc
        .descendants()
        .filter(|n| n.has_tag_name("tr") && n.attribute("id").is_some_and(|i| i.starts_with("eq-")))
        .collect();
    assert_eq!(equations.len(), shown.lines().filter(|l| l.starts_with("assume L")).count());
    for e in &equations {
        let from = e.descendants().filter_map(|n| n.text()).next_back().unwrap_or("");
        assert!(from.starts_with("examples/water_faulty.ld:"), "{from}");
    }
}

/// An integer of the counterexample is a bus track in the diagram and a row of numbers
/// in the table of values: the faulty box's count, the same values as the JSON report
/// of the same run gives at the start of each piece of the time axis.
#[test]
fn an_integer_is_a_bus_track_and_a_row_of_values() {
    let args = ["examples/box_faulty.st", "examples/box.ii", "--only", "Stop"];
    let out = ii_prove(&[&args[..], &["--format", "html"]].concat());
    assert_eq!(out.status.code(), Some(1), "{}", text(&out.stderr));
    let page = text(&out.stdout);
    let doc = parse(&page);
    let bus = doc
        .descendants()
        .find(|n| n.attribute("data-integer") == Some("Count_CV"))
        .expect("a bus track for the count");
    let labels: Vec<&str> =
        bus.descendants().filter(|n| n.has_tag_name("text")).filter_map(|n| n.text()).collect();
    assert!(labels.contains(&"Count_CV") && labels.contains(&"10"), "{labels:?}");
    let row = doc
        .descendants()
        .filter(|n| n.has_tag_name("tr"))
        .find(|r| r.children().any(|c| c.has_tag_name("th") && c.text() == Some("Count_CV")))
        .expect("a row of values");
    let cells: Vec<i64> = row
        .children()
        .filter(|c| c.has_tag_name("td"))
        .map(|c| c.text().unwrap().parse().unwrap())
        .collect();
    let json = ii_prove(&[&args[..], &["--format", "json"]].concat());
    let report: serde_json::Value = serde_json::from_slice(&json.stdout).unwrap();
    let values: Vec<i64> = report["properties"][0]["counterexample"]["integers"][0]["values"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_i64().unwrap())
        .collect();
    // Each piece shows a value the run has; the pieces run through 0 … 10 in order.
    assert!(cells.iter().all(|v| values.contains(v)), "{cells:?} vs {values:?}");
    let mut distinct = cells.clone();
    distinct.dedup();
    assert_eq!(distinct, (0..=10).collect::<Vec<_>>());
}

#[test]
fn html_file_beside_another_format_is_the_same_page() {
    let dir = temp_dir("beside");
    let file = dir.join("report.html");
    let out =
        ii_prove(&[FAULTY[0], FAULTY[1], "--format", "html", "--html", file.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    assert_eq!(std::fs::read_to_string(&file).unwrap(), text(&out.stdout));
    // Beside JUnit: the standard output is JUnit, the file the page.
    let out =
        ii_prove(&[FAULTY[0], FAULTY[1], "--format", "junit", "--html", file.to_str().unwrap()]);
    assert!(text(&out.stdout).contains("<testsuites"));
    let page = std::fs::read_to_string(&file).unwrap();
    parse(&page);
    assert!(page.contains("class=\"track\""));
}

#[test]
fn names_and_paths_are_escaped() {
    let dir = temp_dir("escape");
    let odd = dir.join("r&d <plant>");
    std::fs::create_dir_all(&odd).unwrap();
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    for f in FAULTY {
        std::fs::copy(root.join(f), odd.join(PathBuf::from(f).file_name().unwrap())).unwrap();
    }
    let (ld, ii) = (odd.join("water_faulty.ld"), odd.join("water.ii"));
    let out = ii_prove(&[ld.to_str().unwrap(), ii.to_str().unwrap(), "--format", "html"]);
    assert_eq!(out.status.code(), Some(1));
    let page = text(&out.stdout);
    let doc = parse(&page);
    assert!(doc.descendants().any(|n| n.text().is_some_and(|t| t.contains("r&d <plant>"))));
    links_resolve(&doc);
}

#[test]
fn an_unwritable_html_path_is_refused_before_the_run() {
    let dir = temp_dir("unwritable");
    let missing = dir.join("no/such/folder/report.html");
    let out = ii_prove(&[FAULTY[0], FAULTY[1], "--html", missing.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    assert!(text(&out.stderr).contains("cannot write"), "{}", text(&out.stderr));
    assert!(out.stdout.is_empty(), "no proof ran");
    let out = ii_prove(&[FAULTY[0], FAULTY[1], "--html", dir.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    assert!(text(&out.stderr).contains("is a directory"));
    let out = ii_prove(&[FAULTY[0], FAULTY[1], "--html", "-", "--vcd", "-"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(text(&out.stderr).contains("only one of --vcd and --html"), "{}", text(&out.stderr));
}
