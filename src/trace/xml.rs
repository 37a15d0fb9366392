//! A small, strict XML reader for trace files (SINUMERIK Operate traces,
//! Renishaw `.b5r`): elements, attributes and text, each element with the
//! line it starts on.
//!
//! Reading chosen: well-formedness is checked (every element closed in
//! order, attributes quoted and not repeated, one root, nothing but
//! whitespace, comments and processing instructions outside it); the five
//! predefined entities and character references are read; a `DOCTYPE` is
//! refused (a trace never needs one, and entity definitions are how XML
//! files blow up); namespaces are not resolved (a prefix stays part of the
//! name); CDATA sections are read as text. Nesting deeper than
//! [`MAX_DEPTH`] is refused. Every error names its 1-based line.
//!
//! # Units
//! None: text as written.

use super::TraceError;

/// Deepest nesting read (a trace file has 3–6 levels).
pub const MAX_DEPTH: usize = 64;

/// One element: name, attributes, child elements and text.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Element {
    /// The tag name as written (a namespace prefix kept).
    pub name: String,
    /// Attributes in file order, values with entities replaced.
    pub attrs: Vec<(String, String)>,
    /// Child elements in file order.
    pub children: Vec<Element>,
    /// The element's own text (outside its children), trimmed.
    pub text: String,
    /// 1-based line of its start tag.
    pub line: usize,
}

impl Element {
    /// The value of attribute `name`.
    pub fn attr(&self, name: &str) -> Option<&str> {
        self.attrs
            .iter()
            .find(|(k, _)| k == name)
            .map(|(_, v)| v.as_str())
    }

    /// The first child named `name` (case-insensitive, a namespace prefix
    /// ignored).
    pub fn child(&self, name: &str) -> Option<&Element> {
        self.children.iter().find(|c| c.is(name))
    }

    /// Whether the element is named `name` (case-insensitive, prefix
    /// ignored).
    pub fn is(&self, name: &str) -> bool {
        let local = self.name.rsplit(':').next().unwrap_or(&self.name);
        local.eq_ignore_ascii_case(name)
    }
}

fn err(line: usize, why: impl Into<String>) -> TraceError {
    TraceError::BadXml {
        line,
        why: why.into(),
    }
}

/// Replaces entities and character references in `raw` (on `line`).
fn unescape(raw: &str, line: usize) -> Result<String, TraceError> {
    if !raw.contains('&') {
        return Ok(raw.to_string());
    }
    let mut out = String::with_capacity(raw.len());
    let mut rest = raw;
    while let Some(i) = rest.find('&') {
        out.push_str(&rest[..i]);
        let after = &rest[i + 1..];
        let end = after
            .find(';')
            .filter(|&e| e <= 12)
            .ok_or_else(|| err(line, "'&' without its ';': write '&amp;' for an ampersand"))?;
        let name = &after[..end];
        let c = match name {
            "lt" => Some('<'),
            "gt" => Some('>'),
            "amp" => Some('&'),
            "quot" => Some('"'),
            "apos" => Some('\''),
            _ => {
                let code = if let Some(h) = name.strip_prefix("#x") {
                    u32::from_str_radix(h, 16).ok()
                } else if let Some(d) = name.strip_prefix('#') {
                    d.parse().ok()
                } else {
                    None
                };
                code.and_then(char::from_u32)
            }
        };
        out.push(c.ok_or_else(|| err(line, format!("unknown entity '&{name};'")))?);
        rest = &after[end + 1..];
    }
    out.push_str(rest);
    Ok(out)
}

/// A cursor over the text that counts lines.
struct Cursor<'a> {
    s: &'a str,
    pos: usize,
    line: usize,
}

impl<'a> Cursor<'a> {
    fn rest(&self) -> &'a str {
        &self.s[self.pos..]
    }

    /// Moves `n` bytes on, counting newlines.
    fn advance(&mut self, n: usize) {
        let end = (self.pos + n).min(self.s.len());
        self.line += self.s.as_bytes()[self.pos..end]
            .iter()
            .filter(|&&b| b == b'\n')
            .count();
        self.pos = end;
    }

    /// Moves past the next `pat`, or errors with `what` at the start line.
    fn skip_past(&mut self, pat: &str, what: &str) -> Result<&'a str, TraceError> {
        let line = self.line;
        let rest = self.rest();
        match rest.find(pat) {
            Some(i) => {
                self.advance(i + pat.len());
                Ok(&rest[..i])
            }
            None => Err(err(line, format!("{what} is not closed ('{pat}' missing)"))),
        }
    }

    fn skip_space(&mut self) {
        let n = self.rest().len() - self.rest().trim_start().len();
        self.advance(n);
    }

    /// A name (tag or attribute).
    fn name(&mut self) -> &'a str {
        let rest = self.rest();
        let n = rest
            .find(|c: char| c.is_whitespace() || matches!(c, '=' | '>' | '/' | '<' | '"' | '\''))
            .unwrap_or(rest.len());
        self.advance(n);
        &rest[..n]
    }
}

/// Reads the start tag after `<` into an element; `true` when it closes
/// itself (`/>`).
fn start_tag(c: &mut Cursor) -> Result<(Element, bool), TraceError> {
    let line = c.line;
    let name = c.name();
    if name.is_empty() {
        return Err(err(line, "'<' is not followed by a tag name"));
    }
    let mut el = Element {
        name: name.to_string(),
        line,
        ..Element::default()
    };
    loop {
        c.skip_space();
        let rest = c.rest();
        if rest.starts_with("/>") {
            c.advance(2);
            return Ok((el, true));
        }
        if rest.starts_with('>') {
            c.advance(1);
            return Ok((el, false));
        }
        if rest.is_empty() {
            return Err(err(
                line,
                format!("start tag <{name}> is not closed ('>' missing)"),
            ));
        }
        let at = c.line;
        let key = c.name();
        if key.is_empty() {
            return Err(err(
                at,
                format!(
                    "in <{name}>: '{}' where an attribute name was expected",
                    rest.chars().next().unwrap_or(' ')
                ),
            ));
        }
        c.skip_space();
        if !c.rest().starts_with('=') {
            return Err(err(
                at,
                format!("in <{name}>: attribute '{key}' has no '=' and value"),
            ));
        }
        c.advance(1);
        c.skip_space();
        let q = match c.rest().chars().next() {
            Some(q @ ('"' | '\'')) => q,
            _ => {
                return Err(err(
                    at,
                    format!("in <{name}>: the value of '{key}' is not in quotes"),
                ))
            }
        };
        c.advance(1);
        let raw = c.skip_past(&q.to_string(), &format!("the value of '{key}'"))?;
        if raw.contains('<') {
            return Err(err(
                at,
                format!("in <{name}>: the value of '{key}' contains '<'"),
            ));
        }
        if el.attr(key).is_some() {
            return Err(err(
                at,
                format!("in <{name}>: attribute '{key}' is repeated"),
            ));
        }
        el.attrs.push((key.to_string(), unescape(raw, at)?));
    }
}

/// Newlines before the first non-blank character of `s`.
fn leading_lines(s: &str) -> usize {
    let lead = s.len() - s.trim_start().len();
    s[..lead].matches('\n').count()
}

/// Parses `text` into its root element.
///
/// # Errors
/// [`TraceError::BadXml`] naming the line and what is wrong.
///
/// # Examples
/// ```
/// use mtmotion::trace::xml::parse;
/// let root = parse("<?xml version=\"1.0\"?>\n<a x=\"1 &amp; 2\">\n <b/>hi</a>\n").unwrap();
/// assert_eq!((root.attr("x"), root.children[0].line, root.text.as_str()), (Some("1 & 2"), 3, "hi"));
/// let e = parse("<a>\n<b>\n</a>\n").unwrap_err().to_string();
/// assert_eq!(e, "line 3: XML: </a> closes <b> (opened on line 2); close <b> first");
/// ```
pub fn parse(text: &str) -> Result<Element, TraceError> {
    let mut c = Cursor {
        s: text.strip_prefix('\u{feff}').unwrap_or(text),
        pos: 0,
        line: 1,
    };
    let mut stack: Vec<Element> = Vec::new();
    let mut root: Option<Element> = None;
    loop {
        let rest = c.rest();
        let Some(lt) = rest.find('<') else {
            if let Some(open) = stack.last() {
                return Err(err(
                    c.line,
                    format!(
                        "the file ends inside <{}> (opened on line {})",
                        open.name, open.line
                    ),
                ));
            }
            if !rest.trim().is_empty() {
                return Err(err(
                    c.line + leading_lines(rest),
                    "text after the root element",
                ));
            }
            break;
        };
        let txt = &rest[..lt];
        match stack.last_mut() {
            Some(top) => {
                let t = unescape(txt.trim(), c.line)?;
                if !t.is_empty() {
                    if !top.text.is_empty() {
                        top.text.push(' ');
                    }
                    top.text.push_str(&t);
                }
            }
            None if !txt.trim().is_empty() => {
                let at = c.line + leading_lines(txt);
                return Err(err(
                    at,
                    format!(
                        "text '{}' outside the root element",
                        super::clip(txt.trim())
                    ),
                ));
            }
            None => {}
        }
        c.advance(lt);
        let rest = c.rest();
        if rest.starts_with("<?") {
            c.skip_past("?>", "a processing instruction")?;
        } else if rest.starts_with("<!--") {
            c.skip_past("-->", "a comment")?;
        } else if rest.starts_with("<![CDATA[") {
            let line = c.line;
            c.advance(9);
            let data = c.skip_past("]]>", "a CDATA section")?;
            match stack.last_mut() {
                Some(top) => top.text.push_str(data.trim()),
                None => return Err(err(line, "CDATA outside the root element")),
            }
        } else if rest.starts_with("<!") {
            return Err(err(
                c.line,
                "a DOCTYPE or other declaration is not read in a trace file",
            ));
        } else if rest.starts_with("</") {
            let line = c.line;
            c.advance(2);
            let name = c.name();
            c.skip_space();
            if !c.rest().starts_with('>') {
                return Err(err(
                    line,
                    format!("end tag </{name}> is not closed ('>' missing)"),
                ));
            }
            c.advance(1);
            let Some(el) = stack.pop() else {
                return Err(err(line, format!("</{name}> closes no open element")));
            };
            if el.name != name {
                return Err(err(
                    line,
                    format!(
                        "</{name}> closes <{}> (opened on line {}); close <{}> first",
                        el.name, el.line, el.name
                    ),
                ));
            }
            match stack.last_mut() {
                Some(parent) => parent.children.push(el),
                None => root = Some(el),
            }
        } else {
            let line = c.line;
            c.advance(1);
            if root.is_some() {
                return Err(err(line, "a second root element; an XML file has one"));
            }
            let (el, closed) = start_tag(&mut c)?;
            if closed {
                match stack.last_mut() {
                    Some(parent) => parent.children.push(el),
                    None => root = Some(el),
                }
            } else {
                if stack.len() >= MAX_DEPTH {
                    return Err(err(
                        line,
                        format!("elements nested deeper than {MAX_DEPTH} levels"),
                    ));
                }
                stack.push(el);
            }
        }
    }
    root.ok_or_else(|| err(c.line, "no element found"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_elements_attributes_text_and_lines() {
        let src = "\u{feff}<?xml version='1.0'?>\n<!-- c -->\n<r:root a='x' b=\"&lt;&gt;&amp;&quot;&apos;&#65;&#x42;\">\n  <c n=\"1\"/>\n  <c n=\"2\">t<![CDATA[<raw>]]></c>\n</r:root>\n";
        let r = parse(src).unwrap();
        assert!(r.is("ROOT"));
        assert_eq!(
            (r.line, r.attr("a"), r.attr("b")),
            (3, Some("x"), Some("<>&\"'AB"))
        );
        assert_eq!(r.children.len(), 2);
        assert_eq!(r.children[1].line, 5);
        assert_eq!(r.children[1].text, "t<raw>");
        assert_eq!(r.child("c").unwrap().attr("n"), Some("1"));
        assert!(r.child("d").is_none());
    }

    #[test]
    fn malformed_files_are_refused_at_their_line() {
        for (src, line, cause) in [
            (
                "<a>\n<b>\n",
                2,
                "the file ends inside <b> (opened on line 2)",
            ),
            ("<a>\n</b>\n", 2, "</b> closes <a>"),
            ("<a x=1/>", 1, "not in quotes"),
            ("<a\n x='1' x='2'/>", 2, "'x' is repeated"),
            ("<a x/>", 1, "has no '='"),
            ("<a x='&foo;'/>", 1, "unknown entity '&foo;'"),
            ("<a x='a & b'/>", 1, "without its ';'"),
            ("<a/>\n<b/>", 2, "a second root element"),
            ("<a/>\ntext", 2, "text after the root element"),
            ("<a/>\n\n\n  text", 4, "text after the root element"),
            ("\nhello\n<a/>", 2, "outside the root element"),
            ("<!DOCTYPE a [<!ENTITY x 'y'>]>\n<a/>", 1, "DOCTYPE"),
            ("<a>\n<!-- open\n", 2, "a comment is not closed"),
            ("<a\nx='1'", 1, "not closed"),
            ("<a>\n</a\n", 2, "end tag </a> is not closed"),
            ("</a>", 1, "closes no open element"),
            ("< a/>", 1, "not followed by a tag name"),
            ("<a x='<'/>", 1, "contains '<'"),
            ("", 1, "no element found"),
            ("<a>\n<![CDATA[x", 2, "a CDATA section is not closed"),
        ] {
            let e = parse(src).unwrap_err().to_string();
            assert!(
                e.starts_with(&format!("line {line}: XML: ")),
                "{src:?}: {e}"
            );
            assert!(e.contains(cause), "{src:?}: {e}");
        }
        let deep = "<a>".repeat(MAX_DEPTH + 1);
        let e = parse(&deep).unwrap_err().to_string();
        assert!(e.contains("deeper than 64"), "{e}");
    }
}
