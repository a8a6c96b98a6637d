// Fuzz target "surface": the bytes decoded into a triangle/quad soup, which goes through the
// geometry stage's input code (run_surface_chain: check_surface, merging, removal of collapsed
// faces, orientation, node rings, each alone and as prepare_mesh). Seeds: fuzz/corpus/surface/
// (fuzz/make_seeds.py writes them).

#include <strata/core/error.h>

#include "fuzz_support.h"
#include "fuzz_targets.h"
#include "surface_chain.h"

#include <array>

namespace strata::fuzz {
namespace {

constexpr std::array<double, 4> kTolerance = {1e-9, 0.0, 1e-3, 0.3};
constexpr std::array<const char*, 4> kPatchNames = {"wall", "farfield", "symmetry_y0", "inlet"};

/// Break the arrays the way a caller's own code might (what: bits 0-1 which array, bits 2-7 a
/// position; value: the new value): every piece must refuse the mesh, not index through it.
void corrupt(SurfaceMesh& m, std::uint8_t what, std::uint8_t value) {
    if ((what & 3) == 3)  // nodes dropped from the end
        m.points.resize(value % (m.points.size() + 1));
    else  // malformed CSR, a patch entry too few or too many, a negative node id
        corrupt_faces(m, what & 3, what >> 2, value);
}

}  // namespace

/// The soup format, byte by byte (every byte string decodes to something):
///
///   flags      bit 0     PrepareParams::internal_flow
///              bits 1-2  merge tolerance: 1e-9 (the default), 0, 1e-3, 0.3
///              bit 3     the patch mapping inlet=other (an InputError with fewer than 4 patches)
///              bits 4-5  number of patches - 1; they are "wall", "farfield", "symmetry_y0",
///                        "inlet" (kinds from the names)
///              bit 6     PrepareParams::scale 1000 instead of 1
///              bit 7     corrupt the arrays after decoding: two more bytes, what and value
///                        (corrupt() above)
///   N          number of nodes, 0-255
///   N nodes    each a byte and what follows it (decode_point, fuzz_support.h: a grid point, moved
///              or not, one coordinate special, or three raw doubles)
///   faces      until the end, a header byte h and 3 (h bit 0 clear) or 4 ids each:
///              bits 1-2  patch (modulo the number of patches), or with bit 4 set (h >> 5) - 1,
///                        which may be out of range
///              bit 3     ids taken as they are (may be out of range) instead of modulo N
///              A face cut short by the end is left out.
Soup decode_soup(const std::uint8_t* data, std::size_t size) {
    Soup soup;
    SurfaceMesh& m = soup.mesh;
    Bytes in(data, size);
    std::uint8_t flags = 0, what = 0, value = 0;
    if (!in.byte(flags)) return soup;
    const bool corrupted = (flags & 0x80) && in.byte(what) && in.byte(value);
    soup.params.internal_flow = flags & 1;
    soup.params.merge_tolerance = kTolerance[(flags >> 1) & 3u];
    if (flags & 8) soup.params.patch_kinds.emplace_back("inlet", PatchKind::Other);
    const unsigned num_patches = ((flags >> 4) & 3u) + 1;
    for (unsigned p = 0; p < num_patches; ++p) m.patches.push_back({kPatchNames[p], PatchKind::Wall});
    if (flags & 0x40) soup.params.scale = 1000.0;

    if (!decode_points(in, m.points)) return soup;
    const auto n = static_cast<Index>(m.points.size());

    for (std::uint8_t h = 0; in.byte(h);) {
        const Index k = (h & 1) ? 4 : 3;
        std::array<Index, 4> v{};
        if (!decode_ids(in, k, h & 8, n, v.data())) break;
        const Index patch = (h & 16) ? Index{h >> 5} - 1 : Index{(h >> 1) & 3} % static_cast<Index>(num_patches);
        m.add_face(v.data(), k, patch);
    }
    if (corrupted) corrupt(m, what, value);
    return soup;
}

}  // namespace strata::fuzz

int strata_fuzz_one_surface(const std::uint8_t* data, std::size_t size) {
    const strata::fuzz::Soup soup = strata::fuzz::decode_soup(data, size);
    strata::fuzz::run_surface_chain(soup.mesh, soup.params, "fuzz soup");
    return 0;
}

#ifdef STRATA_LIBFUZZER
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return strata_fuzz_one_surface(data, size);
}
#endif
