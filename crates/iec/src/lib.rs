//! IEC 61131-3 value semantics.
