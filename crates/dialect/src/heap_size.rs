//! The size of the CODESYS heap (`__NEW`/`__DELETE`): 65536 bytes unless
//! the project says otherwise, `--lib codesys:heap=256KiB` or
//! `[codesys] heap = "256KiB"` in `automat.toml`. The library
//! (`lib/codesys.st`) declares the size as two constants; a project's size
//! is written into them before the library is parsed.

/// The heap of a project that sets none (CODESYS V3's default order of
/// magnitude for small targets).
pub const DEFAULT_HEAP_BYTES: u32 = 65536;

/// The smallest heap: one block header and 8 bytes.
pub const MIN_HEAP_BYTES: u32 = 16;

/// The largest heap: a quarter of the memory image, which must still hold
/// the program's own variables.
pub const MAX_HEAP_BYTES: u32 = 64 << 20;

const BYTES_LINE: &str = "    __HEAP_BYTES : DWORD := 65536;";
const LAST_LINE: &str = "    __HEAP_LAST : DINT := 8191;";

/// A heap size as written (`65536`, `512B`, `64KiB`, `1MiB`, any case,
/// spaces around the unit allowed): its bytes, or why it is not one.
pub fn parse_heap_size(text: &str) -> Result<u32, String> {
    let t = text.trim();
    let digits = t.find(|c: char| !c.is_ascii_digit()).unwrap_or(t.len());
    let (number, unit) = t.split_at(digits);
    let scale: u64 = match unit.trim().to_ascii_lowercase().as_str() {
        "" | "b" => 1,
        "kib" => 1 << 10,
        "mib" => 1 << 20,
        other => {
            return Err(format!(
                "heap size `{t}`: unknown unit `{other}` (write bytes, `KiB` or `MiB`: `256KiB`)"
            ))
        }
    };
    let Ok(n) = number.parse::<u64>() else {
        return Err(format!(
            "heap size `{t}` is not a number of bytes, `KiB` or `MiB` (`65536`, `256KiB`, `1MiB`)"
        ));
    };
    let bytes = n.saturating_mul(scale);
    if bytes < u64::from(MIN_HEAP_BYTES) || bytes > u64::from(MAX_HEAP_BYTES) {
        return Err(format!(
            "heap size `{t}` ({bytes} bytes) is outside {MIN_HEAP_BYTES} bytes .. 64MiB"
        ));
    }
    if bytes % 8 != 0 {
        return Err(format!(
            "heap size `{t}` ({bytes} bytes) is not a multiple of 8 (the heap's blocks are)"
        ));
    }
    u32::try_from(bytes).map_err(|_| format!("heap size `{t}` is too large"))
}

/// The CODESYS library with a heap of `bytes` (a size [`parse_heap_size`]
/// accepted).
pub fn codesys_library(source: &str, bytes: u32) -> String {
    if bytes == DEFAULT_HEAP_BYTES {
        return source.to_string();
    }
    source
        .replace(BYTES_LINE, &format!("    __HEAP_BYTES : DWORD := {bytes};"))
        .replace(
            LAST_LINE,
            &format!("    __HEAP_LAST : DINT := {};", bytes / 8 - 1),
        )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_parse_exactly() {
        assert_eq!(parse_heap_size("65536"), Ok(65536));
        assert_eq!(parse_heap_size("256KiB"), Ok(262_144));
        assert_eq!(parse_heap_size(" 1 mib "), Ok(1_048_576));
        assert_eq!(parse_heap_size("64B"), Ok(64));
        assert_eq!(parse_heap_size("16"), Ok(16));
        assert_eq!(parse_heap_size("64MiB"), Ok(64 << 20));
        assert_eq!(
            parse_heap_size("12"),
            Err("heap size `12` (12 bytes) is outside 16 bytes .. 64MiB".into())
        );
        assert_eq!(
            parse_heap_size("100"),
            Err(
                "heap size `100` (100 bytes) is not a multiple of 8 (the heap's blocks are)".into()
            )
        );
        assert_eq!(
            parse_heap_size("65MiB"),
            Err("heap size `65MiB` (68157440 bytes) is outside 16 bytes .. 64MiB".into())
        );
        assert_eq!(
            parse_heap_size("256KB"),
            Err(
                "heap size `256KB`: unknown unit `kb` (write bytes, `KiB` or `MiB`: `256KiB`)"
                    .into()
            )
        );
        assert!(parse_heap_size("").is_err());
        assert!(parse_heap_size("KiB").is_err());
        assert!(parse_heap_size("99999999999999999999999").is_err());
    }

    #[test]
    fn the_library_declares_the_size_once() {
        let lib = include_str!("../lib/codesys.st");
        assert_eq!(lib.matches(BYTES_LINE).count(), 1);
        assert_eq!(lib.matches(LAST_LINE).count(), 1);
        let small = codesys_library(lib, 64);
        assert!(small.contains("    __HEAP_BYTES : DWORD := 64;"));
        assert!(small.contains("    __HEAP_LAST : DINT := 7;"));
        assert_eq!(codesys_library(lib, DEFAULT_HEAP_BYTES), lib);
    }
}
