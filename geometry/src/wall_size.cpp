#include "wall_size.h"

#include <gmsh.h>

#include <algorithm>
#include <cstdlib>

namespace strata {

void EntitySizes::cap(int dim, int tag, double size) {
    const auto [it, fresh] = size_.emplace(std::make_pair(dim, tag), size);
    if (!fresh) it->second = std::min(it->second, size);
}

void EntitySizes::cap_boundary(int dim, int tag, double size) {
    gmsh::vectorpair down;
    gmsh::model::getBoundary({{dim, tag}}, down, false, false, true);  // recursive: down to the points
    for (const auto& [d, t] : down) cap(d, std::abs(t), size);
    if (dim == 2) {
        down.clear();
        gmsh::model::getBoundary({{dim, tag}}, down, false, false, false);  // the curves
        for (const auto& [d, t] : down) cap(d, std::abs(t), size);
    }
}

void EntitySizes::cap_surface(int tag, double size) {
    cap(2, tag, size);
    cap_boundary(2, tag, size);
}

void EntitySizes::cap_curve(int tag, double size) {
    cap(1, tag, size);
    cap_boundary(1, tag, size);
}

SizeCallback::SizeCallback(const EntitySizes& sizes, double factor) : size_(sizes.sizes()) {
    for (auto& [entity, size] : size_) size /= factor;
    gmsh::model::mesh::setSizeCallback([this](int dim, int tag, double, double, double) {
        const auto it = size_.find({dim, tag});
        return it == size_.end() ? 1e22 : it->second;
    });
}

SizeCallback::~SizeCallback() {
    try {
        gmsh::model::mesh::removeSizeCallback();
    } catch (...) {  // Gmsh's API reports through exceptions; a destructor must not throw
    }
}

}  // namespace strata
