#pragma once
/// @file
/// CRC32C (Castagnoli), the checksum of TensorBoard record files and of our checkpoints.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

namespace upkie_rl {

/// CRC32C of `data` (reflected polynomial 0x82F63B78), continuing from `crc` (0 to start).
std::uint32_t crc32c(std::span<const std::byte> data, std::uint32_t crc = 0);

/// CRC32C of the bytes of `text`.
std::uint32_t crc32c(std::string_view text);

/// TensorBoard's masked CRC: ((crc >> 15) | (crc << 17)) + 0xA282EAD8, modulo 2^32.
std::uint32_t mask_crc32c(std::uint32_t crc);

}  // namespace upkie_rl
