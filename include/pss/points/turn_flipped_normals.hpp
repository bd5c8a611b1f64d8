// Normals in a file that contradict the points (issue 26): a part of the cloud whose normals
// were flipped (a scanner's or an exporter's error) leaves APSS and RIMLS a seam where the
// two sides' fits cancel, and `pss project` a cloud oriented half inward. The file's normals
// are turned where the points show such a flip:
// 1. patches: neighbours whose normals agree (n_i·n_j > 0.7) and that are not stacked one
//    above the other join one patch (union-find), so a patch is oriented consistently;
// 2. between two patches, neighbours whose normals are opposed (n_i·n_j < −0.7) are evidence
//    of a flip when they lie side by side, in each other's tangent plane (a seam through one
//    sheet), and evidence against it when stacked (the two faces of a thin wall, a slot, a
//    knife edge: the offset along the normals is most of their distance); stacked pairs that
//    face alike tell nothing (a flipped face of a thin part, or layers: the ground under roofs);
// 3. patches with more seam than wall evidence between them are linked as flipped against
//    each other, strongest evidence first; each group of linked patches whose two sides both
//    hold a patch of 8 samples or more (a file facing one way throughout has none) keeps the
//    side that makes it face outward (facing_vote.hpp: the divergence theorem's sign over the
//    group), or where that has no say and the two sides face opposite ways, the side with
//    more samples, and turns the other; smaller patches face as the surfaces they lie on.
// Creases (normals 90° apart) link nothing, so a CAD part's exact normals are left as they
// are; an orientation that crosses them (orient_normals.hpp) would have to guess.
#pragma once

#include <cstddef>
#include <span>

#include "pss/core/types.hpp"
#include "pss/spatial/support_grid.hpp"

namespace pss {

// `normals`: the grid's samples' unit normals in its sorted order; the neighbours of sample i
// are those within its support ρ_i, the samples that share its fits. Returns how many were
// turned.
std::size_t turn_flipped_normals(const SupportGrid& grid, std::span<vec3> normals);

}  // namespace pss
