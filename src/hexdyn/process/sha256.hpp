#pragma once
/// \file sha256.hpp
/// SHA-256 (FIPS 180-4) of files and byte strings, by OpenSSL's libcrypto (its EVP
/// digest interface; the implementation FIPS 140 validations cover). hexdyn records the
/// digest of every input file a run, sweep or envelope reads (config/inputs.hpp,
/// docs/user/output.md#provenance-of-the-inputs).
#include <cstddef>
#include <string>

namespace hexdyn {

/// SHA-256 of `size` bytes at `data`: 64 lowercase hexadecimal digits.
std::string sha256_hex(const void* data, std::size_t size);

/// SHA-256 of a file's contents (read whole, in 64 KiB blocks): 64 lowercase hexadecimal
/// digits, as `sha256sum` prints them. Throws IoError "cannot hash input file 'PATH': why"
/// when the file cannot be opened or read, or is not a regular file (a FIFO or device is
/// refused before it is opened).
std::string sha256_file(const std::string& path);

}  // namespace hexdyn
