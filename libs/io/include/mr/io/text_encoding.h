#pragma once
// Names (OBJ groups and materials, PLY region comments, glTF material names)
// are bytes in the files we read, often Latin-1 or Windows-1252 from older
// exporters. Every writer that emits a name passes it through as_utf8, so
// what we write is valid UTF-8 whatever came in: glTF requires it (JSON), and
// one encoding across formats keeps a name the same after any round trip.

#include <string>
#include <string_view>

namespace mr::io {

/// True if `text` is well-formed UTF-8 (RFC 3629: no overlong forms, no
/// surrogates, nothing above U+10FFFF).
bool is_utf8(std::string_view text);

/// `text` as UTF-8: well-formed UTF-8 sequences are kept as they are; every
/// other byte is decoded as Windows-1252 (Latin-1 with printable 0x80-0x9F;
/// its five unassigned bytes become the C1 controls of the same value).
std::string as_utf8(std::string_view text);

}  // namespace mr::io
