//! What XML 1.0 can hold: the VTU writer and the SVG figures both carry
//! user text (titles, labels, field names), which must never make a file
//! ill-formed.

/// Whether XML 1.0 allows `c` in a document at all (its `Char` production):
/// tab, line feed, carriage return and everything from U+0020 up, except
/// U+FFFE and U+FFFF. Control characters cannot even be escaped.
pub(crate) fn xml_char_allowed(c: char) -> bool {
    matches!(c, '\t' | '\n' | '\r') || (c >= ' ' && c != '\u{FFFE}' && c != '\u{FFFF}')
}

/// `s` with every character XML cannot hold replaced by U+FFFD, so that
/// user text (titles, labels) never makes a file ill-formed.
pub(crate) fn xml_safe(s: &str) -> std::borrow::Cow<'_, str> {
    if s.chars().all(xml_char_allowed) {
        std::borrow::Cow::Borrowed(s)
    } else {
        s.chars()
            .map(|c| if xml_char_allowed(c) { c } else { '\u{FFFD}' })
            .collect::<String>()
            .into()
    }
}
