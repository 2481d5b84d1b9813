//! Text from the user (file names, batch cells, model files, error messages) escaped for the
//! format it is written into: a CSV cell that a spreadsheet would read as a formula is
//! neutralised, a Markdown cell cannot open HTML, a link or a new column. (HTML pages escape
//! through their template engine; terminals through `term`.)

use std::borrow::Cow;

/// A CSV text cell that a spreadsheet shows as text: one that begins with `=`, `+`, `-`, `@`,
/// a tab or a carriage return (read as a formula or a command by Excel, LibreOffice and
/// Google Sheets) gets a leading apostrophe, as OWASP's advice on CSV injection has it. For
/// text only: a number this program formats is written as it is.
pub fn csv_text(text: &str) -> Cow<'_, str> {
    match text.chars().next() {
        Some('=' | '+' | '-' | '@' | '\t' | '\r') => Cow::Owned(format!("'{text}")),
        _ => Cow::Borrowed(text),
    }
}

/// A Markdown table cell's text: `&`, `<` and `>` as HTML entities (no tag, no comment), `|`,
/// `[`, `]` and `\` escaped (no new column, no link), line breaks as spaces and other control
/// characters escaped.
pub fn md_text(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in crate::term::one_line(&text.replace(['\n', '\r'], " ")).chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '|' | '[' | ']' | '\\' => {
                out.push('\\');
                out.push(c);
            }
            c => out.push(c),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spreadsheet_formulas_are_neutralised_and_plain_text_kept() {
        for bad in [
            "=HYPERLINK(\"x\")",
            "+1+2",
            "-2+3",
            "@SUM(A1)",
            "\tx",
            "\rx",
        ] {
            assert_eq!(csv_text(bad), format!("'{bad}"));
        }
        assert!(matches!(csv_text("spring-k705.mp4"), Cow::Borrowed(_)));
        assert_eq!(csv_text(""), "");
    }

    #[test]
    fn markdown_cells_cannot_open_html_links_or_columns() {
        assert_eq!(
            md_text("<img src=x onerror=alert(1)>|[a](b)\nc\u{1b}"),
            // The escape shown as text, its backslash escaped for Markdown.
            "&lt;img src=x onerror=alert(1)&gt;\\|\\[a\\](b) c\\\\x1b"
        );
        assert_eq!(md_text("g_over_l = 9.15 s^-2"), "g_over_l = 9.15 s^-2");
    }
}
