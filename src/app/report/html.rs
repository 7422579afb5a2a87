//! The page: one HTML document with its style inline, a policy that lets
//! it fetch nothing, numbered sections with a table of contents, tables and
//! pictures. Every text that comes from the folder is escaped here.

use std::fmt::Write as _;

/// The page's style: print-friendly, sans-serif, tables with rules.
const STYLE: &str = "body{font-family:sans-serif;max-width:60rem;margin:1.5rem auto;padding:0 1rem;color:#111;line-height:1.4}\
h1{font-size:1.6rem;margin-bottom:.2rem}h2{font-size:1.3rem;border-bottom:2px solid #333;margin-top:2rem;page-break-after:avoid}\
h3{font-size:1.1rem;margin-top:1.4rem;page-break-after:avoid}\
table{border-collapse:collapse;margin:.6rem 0;font-size:.88rem;page-break-inside:avoid}\
th,td{border:1px solid #999;padding:.2rem .45rem;text-align:left;vertical-align:top}th{background:#eee}\
td.n{text-align:right;white-space:nowrap}\
.pass{background:#d7f0d2;color:#0b5a0b;font-weight:bold}.fail{background:#f8d0cc;color:#8a1010;font-weight:bold}\
.absent{color:#666;font-style:italic}.warn{background:#fff4cc;border-left:4px solid #d9a400;padding:.3rem .6rem;margin:.4rem 0}\
figure{margin:.8rem 0;page-break-inside:avoid}figcaption{font-size:.85rem;color:#333}\
svg{max-width:100%;height:auto}.swatch{display:inline-block;width:1.6em;height:.9em;border:1px solid #555;vertical-align:middle;margin:0 .3em 0 .8em}\
nav ol{columns:2}@media print{nav{display:none}body{max-width:none}}";

/// `text` with `& < > " '` as entities.
pub(super) fn esc(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            c => out.push(c),
        }
    }
    out
}

/// A table cell: its text (escaped when written) and a class (`n` for a
/// number, `pass`, `fail`).
pub(super) struct Cell {
    pub text: String,
    pub class: &'static str,
}

impl Cell {
    /// A number (right-aligned).
    pub fn n(text: String) -> Cell {
        Cell { text, class: "n" }
    }
}

impl From<String> for Cell {
    fn from(text: String) -> Cell {
        Cell { text, class: "" }
    }
}

impl From<&str> for Cell {
    fn from(text: &str) -> Cell {
        Cell::from(text.to_string())
    }
}

/// The page as it is built: its sections' HTML and their headings.
#[derive(Default)]
pub(super) struct Page {
    body: String,
    sections: Vec<(String, String)>,
}

impl Page {
    /// A numbered section `id` with its heading.
    pub fn section(&mut self, id: &str, title: &str) {
        let n = self.sections.len() + 1;
        let _ = write!(self.body, "<h2 id=\"{id}\">{n}. {}</h2>", esc(title));
        self.sections.push((id.to_string(), title.to_string()));
    }

    /// A sub-heading.
    pub fn heading(&mut self, title: &str) {
        let _ = write!(self.body, "<h3>{}</h3>", esc(title));
    }

    /// A paragraph of text.
    pub fn text(&mut self, text: &str) {
        let _ = write!(self.body, "<p>{}</p>", esc(text));
    }

    /// A line saying what is absent.
    pub fn absent(&mut self, text: &str) {
        let _ = write!(self.body, "<p class=\"absent\">{}</p>", esc(text));
    }

    /// A highlighted warning.
    pub fn warning(&mut self, text: &str) {
        let _ = write!(self.body, "<p class=\"warn\">Warning: {}</p>", esc(text));
    }

    /// HTML made by this module's callers from escaped text and markup of
    /// their own (a picture, a legend).
    pub fn raw(&mut self, html: &str) {
        self.body.push_str(html);
    }

    /// A picture with its caption.
    pub fn figure(&mut self, svg: &str, caption: &str) {
        let _ = write!(
            self.body,
            "<figure>{svg}<figcaption>{}</figcaption></figure>",
            esc(caption)
        );
    }

    /// A table with a caption, a header row and rows of cells.
    pub fn table(&mut self, caption: &str, head: &[&str], rows: Vec<Vec<Cell>>) {
        let b = &mut self.body;
        let _ = write!(b, "<table><caption>{}</caption><thead><tr>", esc(caption));
        for h in head {
            let _ = write!(b, "<th>{}</th>", esc(h));
        }
        b.push_str("</tr></thead><tbody>");
        for row in rows {
            b.push_str("<tr>");
            for c in row {
                match c.class {
                    "" => {
                        let _ = write!(b, "<td>{}</td>", esc(&c.text));
                    }
                    class => {
                        let _ = write!(b, "<td class=\"{class}\">{}</td>", esc(&c.text));
                    }
                }
            }
            b.push_str("</tr>");
        }
        b.push_str("</tbody></table>");
    }

    /// The whole document: head (policy, style), title, contents, sections.
    pub fn finish(self, title: &str, lead: &str) -> String {
        let mut out = String::with_capacity(self.body.len() + 4096);
        out.push_str("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">");
        out.push_str("<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; style-src 'unsafe-inline'; img-src data:\">");
        out.push_str("<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">");
        let _ = write!(
            out,
            "<title>{}</title><style>{STYLE}</style></head><body>",
            esc(title)
        );
        let _ = write!(out, "<h1>{}</h1>{lead}<nav><ol>", esc(title));
        for (id, t) in &self.sections {
            let _ = write!(out, "<li><a href=\"#{id}\">{}</a></li>", esc(t));
        }
        out.push_str("</ol></nav>");
        out.push_str(&self.body);
        out.push_str("</body></html>\n");
        out
    }
}
