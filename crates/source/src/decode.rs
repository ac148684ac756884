//! Source decoding. MicroWIN writes GBK with CRLF line ends; hand-written files are usually UTF-8,
//! sometimes with a BOM. The front end sees one `String` per file either way.

/// Why a file's bytes could not be decoded cleanly.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DecodeIssue {
    /// Byte offset of the first byte that is neither valid UTF-8 nor valid GBK.
    pub byte: usize,
}

/// The text encoding a file turned out to use.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Encoding {
    /// UTF-8, with or without a byte-order mark.
    #[default]
    Utf8,
    /// GBK (code page 936), as written by MicroWIN on Chinese systems.
    Gbk,
    /// Neither; decoded as UTF-8 with replacement characters.
    Lossy,
}

/// Decodes `bytes`: UTF-8 (BOM stripped) first, because valid UTF-8 text is almost never valid
/// GBK by accident for non-ASCII content, then GBK, then lossy UTF-8 with the first bad offset.
pub fn decode(bytes: &[u8]) -> (String, Encoding, Option<DecodeIssue>) {
    let body = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
    match std::str::from_utf8(body) {
        Ok(s) => (s.to_owned(), Encoding::Utf8, None),
        Err(utf8_err) => {
            if let Some(s) =
                encoding_rs::GBK.decode_without_bom_handling_and_without_replacement(body)
            {
                return (s.into_owned(), Encoding::Gbk, None);
            }
            let issue = DecodeIssue {
                byte: utf8_err.valid_up_to() + (bytes.len() - body.len()),
            };
            (
                String::from_utf8_lossy(body).into_owned(),
                Encoding::Lossy,
                Some(issue),
            )
        }
    }
}

/// The bytes of `text` in `encoding` (what a constant string in a file of that encoding
/// stores): UTF-8 for UTF-8 and lossy files, GBK for GBK files (a character GBK cannot hold
/// becomes `?`, which a GBK file cannot contain anyway).
pub fn encode(text: &str, encoding: Encoding) -> Vec<u8> {
    match encoding {
        Encoding::Utf8 | Encoding::Lossy => text.as_bytes().to_vec(),
        Encoding::Gbk => {
            let (bytes, _, _) = encoding_rs::GBK.encode(text);
            bytes.into_owned()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn utf8_with_bom() {
        let (s, e, i) = decode(b"\xEF\xBB\xBFLD I0.0\r\n");
        assert_eq!(s, "LD I0.0\r\n");
        assert_eq!(e, Encoding::Utf8);
        assert!(i.is_none());
    }

    #[test]
    fn encode_keeps_the_file_encoding() {
        assert_eq!(encode("启动", Encoding::Gbk), b"\xC6\xF4\xB6\xAF");
        assert_eq!(encode("启动", Encoding::Utf8), "启动".as_bytes());
        assert_eq!(encode("AB", Encoding::Gbk), b"AB");
    }

    #[test]
    fn gbk_comment() {
        // "启动" in GBK is C6 F4 B6 AF.
        let (s, e, _) = decode(b"LD I0.0 // \xC6\xF4\xB6\xAF\r\n");
        assert_eq!(e, Encoding::Gbk);
        assert_eq!(s, "LD I0.0 // 启动\r\n");
    }

    #[test]
    fn garbage_is_lossy_with_offset() {
        let (_, e, i) = decode(b"LD\xFF\xFF\xFF");
        assert_eq!(e, Encoding::Lossy);
        assert_eq!(i, Some(DecodeIssue { byte: 2 }));
    }
}
