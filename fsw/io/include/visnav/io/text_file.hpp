// Bounded reading of init-time input files, and the guard every TOML text passes before toml++ sees it.
// Shared by every loader in fsw/io and drivers/replay (limits documented in fsw/io/README.md, "Limits").
#pragma once

#include <cstddef>
#include <string>

#include "visnav/core/status.hpp"

namespace visnav::io {

/// Largest file any init-time loader reads. The biggest real input (a detailed .cao model) is well under
/// 1 MiB; the bound keeps a wrong path (a log, an image, /dev/zero behind a link) from costing minutes or
/// all memory. Not a parameter: nothing legitimate comes near it, and a flight unit must not be able to
/// raise it by a config typo.
constexpr std::size_t kMaxInputFileBytes = std::size_t{16} << 20U;

/// Largest TOML file (config, camera, model, sequence): toml++ keeps every value as a node of about a hundred
/// bytes, so a TOML text costs several times its size. The shipped configs are a few kB.
constexpr std::size_t kMaxTomlFileBytes = std::size_t{4} << 20U;

/// Reads the whole of `path` into `text`. The path must name a regular file once links are followed
/// (a FIFO would block, a device never ends) of at most `max_bytes`. Errors name the file and the reason,
/// with the errno text when the system refused ("<path>: cannot open: No such file or directory").
LoadError readTextFile(const std::string& path, std::string& text,
                       std::size_t max_bytes = kMaxInputFileBytes);

/// Same check for a path that is opened elsewhere: a regular file (links followed), size <= max_bytes.
LoadError checkRegularFile(const std::string& path, std::size_t max_bytes = kMaxInputFileBytes);

/// toml++ 3.3.0 has undefined behaviour (a false TOML_ASSERT_ASSUME, __builtin_unreachable in release) on
/// some non-ASCII input (`é = 1`, and non-ASCII after quotes and backslashes, found by tests/fuzz), on a
/// table header that does not start with a key (`[!]`) and on a '}' directly inside an array (`a = [}`).
/// This guard runs before the text reaches the parser: any byte >= 0x80 ("<path>:<line>:<col>: non-ASCII
/// character ...", comments and strings included: visnav's TOML files are ASCII), any control character
/// but tab and line ends, such a table header and such a '}' are rejected.
LoadError checkTomlAscii(const std::string& path, const std::string& text);

}  // namespace visnav::io
