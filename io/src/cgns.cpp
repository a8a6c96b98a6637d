// CGNS writer through the mid-level library (cg_* API), not HDF5 by hand: the CGNS/SIDS layout
// (node names, labels, data types, the version node every reader checks) is the library's.
//
// Cells: one fixed-type section per cell type rather than one MIXED section. The cells are
// already stored that way (fixed-width blocks per type, Gmsh node order, which for linear
// elements is CGNS's), so each section is the block shifted to 1-based ids, with no per-element
// type codes; every CGNS reader handles fixed-type sections, while MIXED changed layout between
// CGNS 3 and 4 (ElementStartOffset) and some solvers' readers take only fixed types. For the
// same reason a boundary patch with both triangles and quadrilaterals becomes two sections,
// consecutive so that the patch is still one element range for its boundary condition.
//
// Element numbering: cells 1..ncells in CellNumbering order, then each patch's faces in
// boundary order (its triangles, then its quadrilaterals). Boundary conditions point at those
// ranges (PointRange, GridLocation FaceCenter: the CGNS 3 form for face elements).

#include <strata/core/error.h>
#include <strata/core/mesh_check.h>
#include <strata/io/cgns.h>
#include <strata/io/files.h>

#include <cgnslib.h>

#include <array>
#include <cerrno>
#include <climits>
#include <cstdint>
#include <set>
#include <string>
#include <vector>

namespace strata {
namespace {

constexpr std::size_t kMaxName = 32;  // CGNS node names: at most 32 characters

/// \p w, or \p w with "_2", "_3", ... (shortened to fit kMaxName) if it is in \p taken; inserted.
std::string take_unique(const std::string& w, std::set<std::string>& taken) {
    std::string name = w.substr(0, kMaxName);
    for (int k = 2; taken.count(name); ++k) {
        std::string suffix = "_";  // appended: GCC 12 warns falsely (-Wrestrict) on "_" + std::string
        suffix += std::to_string(k);
        name = w.substr(0, kMaxName - suffix.size()) + suffix;
    }
    taken.insert(name);
    return name;
}

/// Free bytes below which a failed HDF5 write is taken for a full disk.
constexpr std::int64_t kFullDisk = 1 << 20;

/// Throws BackendError with the CGNS library's message if \p status is not CG_OK.
void check(int status, const std::string& where, const char* what) {
    if (status != CG_OK) throw BackendError(where + what + " failed: " + cg_get_error());
}

/// An open CGNS file, closed on every path (cg_close on an error path too, so the library's
/// file table and HDF5 handles do not leak).
class CgnsFile {
public:
    CgnsFile(const std::string& temp, const std::string& where) : where_(where) {
        check(cg_set_file_type(CG_FILE_HDF5), where_, "cg_set_file_type(HDF5)");
        check(cg_open(temp.c_str(), CG_MODE_WRITE, &fn_), where_, "cg_open");
    }
    ~CgnsFile() {
        if (fn_ >= 0) cg_close(fn_);
    }
    CgnsFile(const CgnsFile&) = delete;
    CgnsFile& operator=(const CgnsFile&) = delete;
    int fn() const { return fn_; }
    void close() {
        const int fn = fn_;
        fn_ = -1;
        check(cg_close(fn), where_, "cg_close");
    }

private:
    std::string where_;
    int fn_ = -1;
};

CGNS_ENUMT(BCType_t) bc_type(PatchKind kind) {
    switch (kind) {
        case PatchKind::Wall:
            return CGNS_ENUMV(BCWall);
        case PatchKind::Symmetry:
            return CGNS_ENUMV(BCSymmetryPlane);
        case PatchKind::Farfield:
            return CGNS_ENUMV(BCFarfield);
        case PatchKind::Other:
            break;
    }
    return CGNS_ENUMV(BCTypeUserDefined);  // an outflow plane, a layer side: the family name says which
}

constexpr std::array<const char*, 4> kSectionName{"Tetrahedra", "Pyramids", "Prisms", "Hexahedra"};
constexpr std::array<CGNS_ENUMT(ElementType_t), 4> kElementType{CGNS_ENUMV(TETRA_4), CGNS_ENUMV(PYRA_5),
                                                                CGNS_ENUMV(PENTA_6), CGNS_ENUMV(HEXA_8)};

}  // namespace

std::vector<std::string> cgns_names(const std::vector<std::string>& names, const std::vector<std::string>& reserved) {
    std::set<std::string> taken(reserved.begin(), reserved.end());
    std::vector<std::string> out;
    for (std::size_t i = 0; i < names.size(); ++i) {
        std::string w = names[i];
        for (char& c : w)
            if (c == '/' || static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '_';
        if (w.find_first_not_of(' ') == std::string::npos) w = "patch_" + std::to_string(i + 1);
        out.push_back(take_unique(w, taken));
    }
    return out;
}

void write_cgns(const VolumeMesh& mesh, const std::string& path, Progress* progress, OutputSet* outputs) {
    report(progress, "writing", 0.0);
    const std::string where = "cannot write CGNS file '" + path + "': ";
    require_sound(check_volume_arrays(mesh), where);
    const SurfaceMesh& b = mesh.boundary;
    const std::int64_t nelements = static_cast<std::int64_t>(mesh.num_cells()) + b.num_faces();
    if (nelements > INT_MAX || static_cast<std::int64_t>(mesh.points.size()) > INT_MAX)
        throw InputError(where + std::to_string(nelements) +
                         " elements: more than this CGNS library's 32-bit sizes hold");

    // Names: patches (their BC, family and section), unique among each other and the zone's and
    // base's other children.
    std::vector<std::string> reserved{"Fluid", "GridCoordinates", "ZoneBC", "ZoneType", "FamilyName"};
    reserved.insert(reserved.end(), kSectionName.begin(), kSectionName.end());
    std::vector<std::string> patch_names;
    for (const Patch& p : b.patches) patch_names.push_back(p.name);
    patch_names = cgns_names(patch_names, reserved);
    std::set<std::string> taken(reserved.begin(), reserved.end());
    taken.insert(patch_names.begin(), patch_names.end());

    // Each patch's triangles and quadrilaterals, 1-based node ids, in boundary order.
    const std::size_t npatches = b.patches.size();
    std::vector<std::vector<cgsize_t>> tris(npatches), quads(npatches);
    for (Index f = 0; f < b.num_faces(); ++f) {
        auto& to = b.face_size(f) == 3 ? tris : quads;
        for (const Index* v = b.face_begin(f); v != b.face_end(f); ++v)
            to[static_cast<std::size_t>(b.face_patch[f])].push_back(static_cast<cgsize_t>(*v) + 1);
    }

    OutputSet own;
    AtomicFile& out = (outputs ? *outputs : own).file(path);  // InputError now if the directory does not exist
    try {
        CgnsFile file(out.temp_path(), where);
        const int fn = file.fn();
        int B = 0, Z = 0, C = 0, S = 0;
        check(cg_base_write(fn, "Base", 3, 3, &B), where, "cg_base_write");
        const std::array<cgsize_t, 3> size{static_cast<cgsize_t>(mesh.points.size()),
                                           static_cast<cgsize_t>(mesh.num_cells()), 0};
        check(cg_zone_write(fn, B, "Fluid", size.data(), CGNS_ENUMV(Unstructured), &Z), where, "cg_zone_write");

        std::vector<double> coord(mesh.points.size());
        constexpr std::array<const char*, 3> kCoord{"CoordinateX", "CoordinateY", "CoordinateZ"};
        for (int d = 0; d < 3; ++d) {
            for (std::size_t i = 0; i < mesh.points.size(); ++i) coord[i] = mesh.points[i][d];
            check(
                cg_coord_write(fn, B, Z, CGNS_ENUMV(RealDouble), kCoord[static_cast<std::size_t>(d)], coord.data(), &C),
                where, "cg_coord_write");
        }
        report(progress, "writing", 0.2);

        cgsize_t next = 1;  // the next element number
        std::vector<cgsize_t> conn;
        for (CellType t : kCellTypes) {
            const std::size_t n = mesh.num_cells(t);
            if (n == 0) continue;
            const std::size_t k = static_cast<std::size_t>(cell_corners(t));
            conn.resize(n * k);
            for (std::size_t i = 0; i < n; ++i) {
                const Index* v = mesh.cell(t, i);
                for (std::size_t j = 0; j < k; ++j) conn[i * k + j] = static_cast<cgsize_t>(v[j]) + 1;
            }
            const auto ti = static_cast<std::size_t>(t);
            const cgsize_t last = next + static_cast<cgsize_t>(n) - 1;
            check(cg_section_write(fn, B, Z, kSectionName[ti], kElementType[ti], next, last, 0, conn.data(), &S), where,
                  "cg_section_write (cells)");
            next = last + 1;
            report(progress, "writing", 0.2 + 0.15 * static_cast<double>(ti + 1));
        }

        for (std::size_t p = 0; p < npatches; ++p) {
            const cgsize_t nt = static_cast<cgsize_t>(tris[p].size() / 3),
                           nq = static_cast<cgsize_t>(quads[p].size() / 4);
            if (nt + nq == 0) continue;
            const std::string& name = patch_names[p];
            const cgsize_t first = next;
            if (nt > 0) {
                check(cg_section_write(fn, B, Z, name.c_str(), CGNS_ENUMV(TRI_3), next, next + nt - 1, 0,
                                       tris[p].data(), &S),
                      where, "cg_section_write (patch triangles)");
                next += nt;
            }
            if (nq > 0) {
                const std::string qname = nt > 0 ? take_unique(name + "_quads", taken) : name;
                check(cg_section_write(fn, B, Z, qname.c_str(), CGNS_ENUMV(QUAD_4), next, next + nq - 1, 0,
                                       quads[p].data(), &S),
                      where, "cg_section_write (patch quadrilaterals)");
                next += nq;
            }

            const CGNS_ENUMT(BCType_t) type = bc_type(b.patches[p].kind);
            int F = 0, FB = 0, BC = 0;
            check(cg_family_write(fn, B, name.c_str(), &F), where, "cg_family_write");
            check(cg_fambc_write(fn, B, F, "FamBC", type, &FB), where, "cg_fambc_write");
            const std::array<cgsize_t, 2> range{first, next - 1};
            check(cg_boco_write(fn, B, Z, name.c_str(), type, CGNS_ENUMV(PointRange), 2, range.data(), &BC), where,
                  "cg_boco_write");
            check(cg_boco_gridlocation_write(fn, B, Z, BC, CGNS_ENUMV(FaceCenter)), where,
                  "cg_boco_gridlocation_write");
            check(cg_goto(fn, B, "Zone_t", Z, "ZoneBC_t", 1, "BC_t", BC, "end"), where, "cg_goto (BC)");
            check(cg_famname_write(name.c_str()), where, "cg_famname_write");
        }
        file.close();
    } catch (const BackendError&) {
        // HDF5 names no cause: a file system left with (almost) nothing free is the cause.
        const std::int64_t free = free_bytes_at(path);
        if (free >= 0 && free < kFullDisk) throw OutputError(write_failure(path, ENOSPC));
        throw;
    }
    // HDF5 can report a full disk only through its own messages: the file is flushed to the
    // device here (OutputSet::commit syncs it again) and its errors named.
    sync_file(out.temp_path(), path);
    report(progress, "writing", 1.0);  // cancelled here: the temporary file goes, nothing is written
    if (!outputs) own.commit();
}

}  // namespace strata
