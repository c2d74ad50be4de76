// UTF-8 validation of names that end up in XML (the XDMF sidecar) and HDF5 attributes: a
// Latin-1 byte or a control character there makes the XDMF file not well-formed (issue 15).
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace cc {

// Byte offset of the first byte that is not part of well-formed UTF-8, or of a control character
// XML 1.0 forbids (below 0x20 except tab, newline, carriage return); nullopt if there is none.
std::optional<std::size_t> firstInvalidUtf8(std::string_view text);

// `text` with every byte outside printable ASCII shown as \xNN, for messages.
std::string escapedBytes(std::string_view text);

}  // namespace cc
