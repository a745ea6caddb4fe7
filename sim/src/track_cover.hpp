#pragma once
// Internal to the virtual machine (layered_engagement.cpp): when does the material a move removed at
// one height stop mattering because moves lower down removed the same? Two stock layers see different
// material only through the moves whose heights lie between them (a helix crossing both). Once the
// XY track of every such move has been run over again by moves wholly below both layers (a helical
// bore's flat bottom circle re-cuts every turn above it), what each layer has lost is the same, and
// from there on the two layers' engagement is the same — the upper layer can share the lower one's.

#include <cstddef>
#include <optional>
#include <vector>

#include "feedplan/geometry/tool_path.hpp"

namespace feedplan::sim::detail {

//! For one lower height z_lo: which earlier moves' tracks re-cut a move's track.
class TrackCover {
 public:
  //! `path` must outlive the object; tracks within `tolerance_mm` of each other count as one.
  TrackCover(const geometry::ToolPath& path, double z_lo_mm, double tolerance_mm);

  //! The number of moves after which move `k`'s XY track (arc, segment or point) lies on the tracks
  //! of moves whose tip stays at or below z_lo, within tolerance_mm_; nullopt when the path never
  //! covers it. Only the tracks are compared, not the tool: every move of one path is cut by one tool.
  std::optional<std::size_t> covered_after(std::size_t k) const;

 private:
  bool is_low(std::size_t j) const;
  std::optional<std::size_t> arc_covered_after(std::size_t k) const;
  std::optional<std::size_t> segment_covered_after(std::size_t k) const;
  std::optional<std::size_t> point_covered_after(std::size_t k) const;

  const geometry::ToolPath& path_;
  double z_lo_mm_;
  double tolerance_mm_;
};

}  // namespace feedplan::sim::detail
