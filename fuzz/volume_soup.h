#pragma once
/// \file
/// Target "writers"' input: a small volume mesh decoded from the fuzzer's bytes.

#include <strata/core/volume_mesh.h>

#include <cstddef>
#include <cstdint>

namespace strata::fuzz {

/// Decode \p data as a volume mesh (the format is described at decode_volume's definition in
/// fuzz/volume_soup.cpp; fuzz/make_seeds.py writes it). Every byte string decodes to some
/// mesh; short input gives an empty one.
VolumeMesh decode_volume(const std::uint8_t* data, std::size_t size);

}  // namespace strata::fuzz
