//! The XML of CEINMS's files read strictly (the subject, the excitation map): a read-only tree
//! (`roxmltree`: no DTD, so no entity expansion; a bounded count of nodes), each element's
//! children among those its schema names, none twice unless a list, values as text.

use muscle_actuator_core::text::{excerpt, one_line};
use roxmltree::{Document, Node, ParsingOptions};

/// Largest XML file read, bytes (1 MiB).
pub(crate) const MAX_XML_BYTES: u64 = muscle_actuator_core::files::MAX_FILE_BYTES;

/// Most nodes (elements, text, attributes) a file may have.
const MAX_NODES: u32 = 1 << 20;

/// What is wrong with an XML file's structure or values; lines count from 1.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum XmlError {
    /// A byte that is not UTF-8.
    #[error("line {line}: not UTF-8 text")]
    NotText {
        /// The line of the first such byte.
        line: usize,
    },
    /// Not well-formed XML (or a DTD, or too many nodes): the parser's reason, with its line and
    /// column.
    #[error("not well-formed XML: {}", one_line(.reason))]
    Parse {
        /// The parser's reason.
        reason: String,
    },
    /// The root element is not the one expected.
    #[error("line {line}: the root element is <{}>, expected <{expected}>", excerpt(.found))]
    WrongRoot {
        /// Its line.
        line: usize,
        /// Its name.
        found: String,
        /// The expected name.
        expected: &'static str,
    },
    /// A required element is missing.
    #[error("line {line}: {within}: no <{element}>")]
    Missing {
        /// The line of the element that lacks it.
        line: usize,
        /// The element that lacks it, as messages name it (`mtu addbrev_r`).
        within: String,
        /// The missing element.
        element: &'static str,
    },
    /// An element given twice where one is expected.
    #[error("line {line}: {within}: a second <{element}>")]
    Duplicate {
        /// The second one's line.
        line: usize,
        /// Its parent, as messages name it.
        within: String,
        /// Its name.
        element: &'static str,
    },
    /// An element the schema does not have there.
    #[error("line {line}: {within}: unknown element <{}> (expected {expected})", excerpt(.element))]
    Unknown {
        /// Its line.
        line: usize,
        /// Its parent, as messages name it.
        within: String,
        /// Its name.
        element: String,
        /// The names allowed there.
        expected: String,
    },
    /// Text beside the child elements of an element that holds elements.
    #[error("line {line}: {within}: text {:?} among the elements", excerpt(.text))]
    StrayText {
        /// The text's line.
        line: usize,
        /// Its parent, as messages name it.
        within: String,
        /// The text, trimmed.
        text: String,
    },
    /// An element in a value.
    #[error("line {line}: {within}: <{element}> holds an element, expected a value")]
    NotAValue {
        /// The inner element's line.
        line: usize,
        /// The value's parent, as messages name it.
        within: String,
        /// The value's element.
        element: String,
    },
    /// A value that is not a finite number.
    #[error("line {line}: {within}: <{element}> {:?} is not a finite number", excerpt(.found))]
    NotANumber {
        /// The value's line.
        line: usize,
        /// Its parent, as messages name it.
        within: String,
        /// The value's element.
        element: String,
        /// The word that is not a number.
        found: String,
    },
    /// A name that is empty.
    #[error("line {line}: {within}: <{element}> is empty")]
    Empty {
        /// The value's line.
        line: usize,
        /// Its parent, as messages name it.
        within: String,
        /// The value's element.
        element: String,
    },
    /// A required attribute is missing.
    #[error("line {line}: {within}: no attribute `{attribute}`")]
    MissingAttribute {
        /// The element's line.
        line: usize,
        /// The element, as messages name it.
        within: String,
        /// The attribute.
        attribute: &'static str,
    },
}

/// Parses `text` (no DTD, at most [`MAX_NODES`] nodes).
pub(super) fn parse(text: &str) -> Result<Document<'_>, XmlError> {
    let options = ParsingOptions {
        allow_dtd: false,
        nodes_limit: MAX_NODES,
        ..ParsingOptions::default()
    };
    Document::parse_with_options(text, options).map_err(|e| XmlError::Parse {
        reason: e.to_string(),
    })
}

/// The root element of `doc`, which must be named `expected`.
pub(crate) fn root<'a, 'i>(
    doc: &'a Document<'i>,
    expected: &'static str,
) -> Result<Node<'a, 'i>, XmlError> {
    let root = doc.root_element();
    if root.tag_name().name() != expected {
        return Err(XmlError::WrongRoot {
            line: line(root),
            found: root.tag_name().name().to_string(),
            expected,
        });
    }
    Ok(root)
}

/// The line (from 1) where `node` starts.
pub(crate) fn line(node: Node) -> usize {
    node.document().text_pos_at(node.range().start).row as usize
}

/// An element and its child elements, each checked to be one its schema allows there.
pub(crate) struct Element<'a, 'i> {
    /// The element.
    pub node: Node<'a, 'i>,
    /// How messages name it (`mtuDefault`, `mtu addbrev_r`).
    pub within: String,
    children: Vec<Node<'a, 'i>>,
}

impl<'a, 'i> Element<'a, 'i> {
    /// `node`'s child elements, each named one of `allowed`; text beside them is refused.
    pub(super) fn new(
        node: Node<'a, 'i>,
        within: String,
        allowed: &[&'static str],
    ) -> Result<Self, XmlError> {
        let mut children = Vec::new();
        for child in node.children() {
            if child.is_text() {
                let text = child.text().unwrap_or("").trim();
                if !text.is_empty() {
                    return Err(XmlError::StrayText {
                        line: line(child),
                        within,
                        text: text.to_string(),
                    });
                }
            } else if child.is_element() {
                if !allowed.contains(&child.tag_name().name()) {
                    return Err(XmlError::Unknown {
                        line: line(child),
                        within,
                        element: child.tag_name().name().to_string(),
                        expected: allowed
                            .iter()
                            .map(|a| format!("<{a}>"))
                            .collect::<Vec<_>>()
                            .join(", "),
                    });
                }
                children.push(child);
            }
        }
        Ok(Element {
            node,
            within,
            children,
        })
    }

    /// The same element named `within` in messages (once its name is read).
    pub(crate) fn named(self, within: String) -> Self {
        Element { within, ..self }
    }

    /// The child elements named `name`, in order.
    pub(crate) fn all(&self, name: &'static str) -> impl Iterator<Item = Node<'a, 'i>> + '_ {
        self.children
            .iter()
            .copied()
            .filter(move |c| c.tag_name().name() == name)
    }

    /// The child element named `name`, if any; a second one is refused.
    pub(crate) fn optional(&self, name: &'static str) -> Result<Option<Node<'a, 'i>>, XmlError> {
        let mut found = self.all(name);
        let first = found.next();
        match found.next() {
            Some(second) => Err(XmlError::Duplicate {
                line: line(second),
                within: self.within.clone(),
                element: name,
            }),
            None => Ok(first),
        }
    }

    /// The child element named `name`, which must be there once.
    pub(crate) fn required(&self, name: &'static str) -> Result<Node<'a, 'i>, XmlError> {
        self.optional(name)?.ok_or_else(|| XmlError::Missing {
            line: line(self.node),
            within: self.within.clone(),
            element: name,
        })
    }

    /// The number in the child element named `name`, which must be there once.
    pub(crate) fn number(&self, name: &'static str) -> Result<f64, XmlError> {
        let node = self.required(name)?;
        number(node, &self.within)
    }

    /// The number in the child element named `name`, if there.
    pub(crate) fn optional_number(&self, name: &'static str) -> Result<Option<f64>, XmlError> {
        self.optional(name)?
            .map(|node| number(node, &self.within))
            .transpose()
    }

    /// The non-empty text (trimmed) of the child element named `name`, which must be there
    /// once.
    pub(crate) fn name(&self, name: &'static str) -> Result<String, XmlError> {
        let node = self.required(name)?;
        let text = value(node, &self.within)?;
        if text.is_empty() {
            return Err(XmlError::Empty {
                line: line(node),
                within: self.within.clone(),
                element: name.to_string(),
            });
        }
        Ok(text)
    }
}

/// The text of `node`, a value (no element inside), trimmed; `within` names its parent.
pub(crate) fn value(node: Node, within: &str) -> Result<String, XmlError> {
    let mut text = String::new();
    for child in node.children() {
        if child.is_element() {
            return Err(XmlError::NotAValue {
                line: line(child),
                within: within.to_string(),
                element: node.tag_name().name().to_string(),
            });
        }
        if let Some(t) = child.text().filter(|_| child.is_text()) {
            text.push_str(t);
        }
    }
    Ok(text.trim().to_string())
}

/// The whitespace-separated words of `node`'s value.
pub(crate) fn words(node: Node, within: &str) -> Result<Vec<String>, XmlError> {
    Ok(value(node, within)?
        .split_ascii_whitespace()
        .map(str::to_string)
        .collect())
}

/// The finite number that is `node`'s value.
pub(crate) fn number(node: Node, within: &str) -> Result<f64, XmlError> {
    let text = value(node, within)?;
    finite(&text, node, within)
}

/// The finite numbers, separated by whitespace, of `node`'s value.
pub(crate) fn numbers(node: Node, within: &str) -> Result<Vec<f64>, XmlError> {
    let text = value(node, within)?;
    text.split_ascii_whitespace()
        .map(|w| finite(w, node, within))
        .collect()
}

/// `word` as a finite number (`node` and `within` name it in the error).
fn finite(word: &str, node: Node, within: &str) -> Result<f64, XmlError> {
    match word.parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        _ => Err(XmlError::NotANumber {
            line: line(node),
            within: within.to_string(),
            element: node.tag_name().name().to_string(),
            found: word.to_string(),
        }),
    }
}

/// The attribute `name` of `node`, which must be there; `within` names the element.
pub(crate) fn attribute<'a>(
    node: Node<'a, '_>,
    within: &str,
    name: &'static str,
) -> Result<&'a str, XmlError> {
    node.attribute(name)
        .ok_or_else(|| XmlError::MissingAttribute {
            line: line(node),
            within: within.to_string(),
            attribute: name,
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn element<'a, 'i>(doc: &'a Document<'i>, allowed: &[&'static str]) -> Element<'a, 'i> {
        Element::new(doc.root_element(), "r".into(), allowed).unwrap()
    }

    #[test]
    fn children_values_and_numbers_read_strictly() {
        let doc = parse("<r>\n <a> 1.5 </a>\n <b>x y\n z</b><!-- c --><n>\n</n></r>").unwrap();
        let r = element(&doc, &["a", "b", "n"]);
        assert_eq!(r.number("a").unwrap(), 1.5);
        assert_eq!(r.optional_number("c").unwrap(), None);
        assert_eq!(
            words(r.required("b").unwrap(), "r").unwrap(),
            ["x", "y", "z"]
        );
        assert_eq!(r.name("a").unwrap(), "1.5");
        assert_eq!(
            r.number("b").unwrap_err().to_string(),
            "line 3: r: <b> \"x y\\n z\" is not a finite number"
        );
        assert_eq!(
            r.name("n").unwrap_err(),
            XmlError::Empty {
                line: 4,
                within: "r".into(),
                element: "n".into()
            }
        );
        assert_eq!(
            r.required("c").unwrap_err().to_string(),
            "line 1: r: no <c>"
        );
    }

    #[test]
    fn unknown_duplicate_stray_and_nested_are_refused() {
        let doc = parse("<r><a>1</a><z/></r>").unwrap();
        let e = Element::new(doc.root_element(), "r".into(), &["a"]).err();
        assert_eq!(
            e.unwrap().to_string(),
            "line 1: r: unknown element <z> (expected <a>)"
        );
        let doc = parse("<r><a>1</a>\n<a>2</a></r>").unwrap();
        let e = element(&doc, &["a"]).number("a").unwrap_err();
        assert_eq!(e.to_string(), "line 2: r: a second <a>");
        let doc = parse("<r>junk<a>1</a></r>").unwrap();
        let e = Element::new(doc.root_element(), "r".into(), &["a"]).err();
        assert!(matches!(e, Some(XmlError::StrayText { .. })), "{e:?}");
        let doc = parse("<r><a>1<b/></a></r>").unwrap();
        let e = element(&doc, &["a"]).number("a").unwrap_err();
        assert!(matches!(e, XmlError::NotAValue { .. }), "{e:?}");
        let doc = parse("<r><a>inf</a></r>").unwrap();
        assert!(element(&doc, &["a"]).number("a").is_err());
    }

    #[test]
    fn malformed_xml_a_dtd_and_a_wrong_root_are_refused() {
        assert!(matches!(parse("<r><a></r>"), Err(XmlError::Parse { .. })));
        let laughs = "<?xml version=\"1.0\"?><!DOCTYPE r [<!ENTITY a \"aaaa\">]><r>&a;</r>";
        assert!(matches!(parse(laughs), Err(XmlError::Parse { .. })));
        let doc = parse("<x/>").unwrap();
        assert_eq!(
            root(&doc, "subject").unwrap_err().to_string(),
            "line 1: the root element is <x>, expected <subject>"
        );
    }
}
