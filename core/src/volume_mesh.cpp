#include <strata/core/enum_names.h>
#include <strata/core/format.h>
#include <strata/core/volume_mesh.h>

namespace strata {

constexpr EnumNames<CellType, 4> kCellTypeNames{{"tetrahedron", "pyramid", "prism", "hexahedron"}};
std::string_view to_string(CellType t) {
    return kCellTypeNames.name(t);
}

std::size_t VolumeMesh::num_cells(CellType t) const {
    return with_cells(t, [](const auto& cells) { return cells.size(); });
}

const Index* VolumeMesh::cell(CellType t, std::size_t i) const {
    return with_cells(t, [i](const auto& cells) { return cells[i].data(); });
}

CellNumbering::CellNumbering(const VolumeMesh& mesh) {
    for (CellType t : kCellTypes) start_[next(t)] = start(t) + static_cast<std::int64_t>(mesh.num_cells(t));
}

CellNumbering::Cell CellNumbering::locate(std::int64_t g) const {
    std::size_t k = 0;
    while (k < 3 && g >= start_[k + 1]) ++k;
    return {kCellTypes[k], g - start_[k]};
}

std::string describe_cell(const VolumeMesh& mesh, CellType t, std::int64_t i) {
    const Index* v = mesh.cell(t, static_cast<std::size_t>(i));
    const int n = cell_corners(t);
    Vec3 c = Vec3::Zero();
    for (int k = 0; k < n; ++k) c += mesh.points[v[k]];
    return std::string(to_string(t)) + " " + std::to_string(i) + " at " + format_point(c / static_cast<double>(n));
}

}  // namespace strata
