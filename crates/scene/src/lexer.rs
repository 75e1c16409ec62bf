//! Tokens of the pbrt scene format, each with its location.

use crate::loc::{Diagnostic, Loc, SourceFile};
use std::sync::Arc;

#[derive(Clone, Debug, PartialEq)]
pub enum TokenKind {
    /// A quoted string, escapes resolved.
    Str(String),
    /// A number; `is_int` when written without '.', 'e' or 'E'.
    Num {
        value: f64,
        is_int: bool,
    },
    /// A bare word: a directive name, or `true`/`false`.
    Ident(String),
    LBracket,
    RBracket,
}

#[derive(Clone, Debug)]
pub struct Token {
    pub kind: TokenKind,
    pub loc: Loc,
}

impl Token {
    /// Short human description, for "expected X, found Y" messages.
    pub fn describe(&self) -> String {
        match &self.kind {
            TokenKind::Str(s) => format!("string \"{s}\""),
            TokenKind::Num { value, .. } => format!("number {value}"),
            TokenKind::Ident(s) => format!("`{s}`"),
            TokenKind::LBracket => "`[`".into(),
            TokenKind::RBracket => "`]`".into(),
        }
    }
}

struct Cursor<'a> {
    text: &'a str,
    pos: usize,
    line: u32,
    col: u32,
}

impl Cursor<'_> {
    fn peek(&self) -> Option<char> {
        self.text[self.pos..].chars().next()
    }

    fn bump(&mut self) -> Option<char> {
        let c = self.peek()?;
        self.pos += c.len_utf8();
        if c == '\n' {
            self.line += 1;
            self.col = 1;
        } else {
            self.col += 1;
        }
        Some(c)
    }
}

fn is_num_char(c: char) -> bool {
    c.is_ascii_digit() || matches!(c, '+' | '-' | '.' | 'e' | 'E')
}

/// Splits a whole file into tokens; the first bad token is an error.
pub fn tokenize(file: &Arc<SourceFile>) -> Result<Vec<Token>, Diagnostic> {
    let mut cur = Cursor {
        text: &file.text,
        pos: 0,
        line: 1,
        col: 1,
    };
    let mut tokens = Vec::new();
    while let Some(c) = cur.peek() {
        let (line, col, start) = (cur.line, cur.col, cur.pos);
        let loc = |len: u32| Loc {
            file: file.clone(),
            line,
            col,
            len,
        };
        if c.is_whitespace() {
            cur.bump();
            continue;
        }
        if c == '#' {
            while let Some(c) = cur.peek() {
                if c == '\n' {
                    break;
                }
                cur.bump();
            }
            continue;
        }
        let kind = if c == '[' {
            cur.bump();
            TokenKind::LBracket
        } else if c == ']' {
            cur.bump();
            TokenKind::RBracket
        } else if c == '"' {
            cur.bump();
            TokenKind::Str(lex_string(&mut cur, &loc)?)
        } else if is_num_char(c) && !matches!(c, 'e' | 'E') {
            // A number cannot start with an exponent: `EndTime` is a word.
            while cur.peek().is_some_and(is_num_char) {
                cur.bump();
            }
            let text = &cur.text[start..cur.pos];
            let value: f64 = text.parse().map_err(|_| {
                Diagnostic::error(&loc(cur.col - col), format!("invalid number `{text}`"))
            })?;
            if !value.is_finite() {
                return Err(Diagnostic::error(
                    &loc(cur.col - col),
                    format!("number `{text}` is out of range"),
                ));
            }
            let is_int = !text.contains(['.', 'e', 'E']);
            TokenKind::Num { value, is_int }
        } else if c.is_alphabetic() || c == '_' {
            while cur.peek().is_some_and(|c| c.is_alphanumeric() || c == '_') {
                cur.bump();
            }
            TokenKind::Ident(cur.text[start..cur.pos].to_string())
        } else {
            return Err(Diagnostic::error(
                &loc(1),
                format!("unexpected character `{c}`"),
            ));
        };
        tokens.push(Token {
            kind,
            loc: loc(cur.col - col),
        });
    }
    Ok(tokens)
}

/// Reads a string body after the opening quote, through the closing quote.
fn lex_string(cur: &mut Cursor, loc: &dyn Fn(u32) -> Loc) -> Result<String, Diagnostic> {
    let start_col = cur.col - 1;
    let mut s = String::new();
    loop {
        let here = cur.col;
        match cur.bump() {
            None | Some('\n') => {
                let len = (here - start_col).max(1);
                return Err(Diagnostic::error(&loc(len), "unterminated string")
                    .with_help("add the closing `\"` on the same line"));
            }
            Some('"') => return Ok(s),
            Some('\\') => {
                let e = cur.bump();
                s.push(match e {
                    Some('n') => '\n',
                    Some('t') => '\t',
                    Some('r') => '\r',
                    Some('b') => '\u{8}',
                    Some('f') => '\u{c}',
                    Some('\\') => '\\',
                    Some('"') => '"',
                    Some('\'') => '\'',
                    other => {
                        let shown = other.map(String::from).unwrap_or_default();
                        let mut l = loc(2);
                        l.col = here;
                        return Err(Diagnostic::error(
                            &l,
                            format!("unknown escape sequence `\\{shown}` in string"),
                        ));
                    }
                });
            }
            Some(c) => s.push(c),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lex(text: &str) -> Result<Vec<Token>, Diagnostic> {
        tokenize(&SourceFile::new("t.pbrt", text))
    }

    #[test]
    fn every_token_kind_with_locations() {
        let toks = lex("Shape \"sphere\" # comment [ 1\n  [ -1 +2.5 .5 1e3 ]\n").unwrap();
        let kinds: Vec<_> = toks.iter().map(|t| t.kind.clone()).collect();
        assert_eq!(
            kinds,
            vec![
                TokenKind::Ident("Shape".into()),
                TokenKind::Str("sphere".into()),
                TokenKind::LBracket,
                TokenKind::Num {
                    value: -1.0,
                    is_int: true
                },
                TokenKind::Num {
                    value: 2.5,
                    is_int: false
                },
                TokenKind::Num {
                    value: 0.5,
                    is_int: false
                },
                TokenKind::Num {
                    value: 1000.0,
                    is_int: false
                },
                TokenKind::RBracket,
            ]
        );
        let pos: Vec<_> = toks
            .iter()
            .map(|t| (t.loc.line, t.loc.col, t.loc.len))
            .collect();
        assert_eq!(
            pos,
            vec![
                (1, 1, 5),
                (1, 7, 8),
                (2, 3, 1),
                (2, 5, 2),
                (2, 8, 4),
                (2, 13, 2),
                (2, 16, 3),
                (2, 20, 1)
            ]
        );
    }

    #[test]
    fn escapes() {
        let toks = lex(r#""a\"b\\c\nd\te""#).unwrap();
        assert_eq!(toks[0].kind, TokenKind::Str("a\"b\\c\nd\te".into()));
    }

    #[test]
    fn unterminated_string_is_an_error_with_caret() {
        let e = lex("Shape\n  \"sphere\n").unwrap_err();
        let s = e.to_string();
        assert!(s.contains("t.pbrt:2:3: error: unterminated string"), "{s}");
        assert!(s.contains('^'), "{s}");
    }

    #[test]
    fn stray_character_and_bad_number() {
        let e = lex("Shape {").unwrap_err();
        assert!(e.to_string().contains("t.pbrt:1:7"), "{e}");
        assert!(e.message.contains("unexpected character `{`"));
        let e = lex("Translate 1.2.3 0 0").unwrap_err();
        assert!(e.message.contains("invalid number `1.2.3`"), "{e}");
        assert_eq!(
            (e.loc.as_ref().unwrap().col, e.loc.as_ref().unwrap().len),
            (11, 5)
        );
        let e = lex("\"a\\q\"").unwrap_err();
        assert!(e.message.contains("escape"), "{e}");
    }

    #[test]
    fn crlf_and_unicode_columns() {
        let toks = lex("\"é\" x\r\ny").unwrap();
        assert_eq!((toks[1].loc.line, toks[1].loc.col), (1, 5));
        assert_eq!((toks[2].loc.line, toks[2].loc.col), (2, 1));
    }
}
