#pragma once
// The stock as the virtual machine sees it: axial layers, each with the engaged arcs of the tool
// circle along the whole path. Because the material the tool meets at a point of the path does not
// depend on how fast the tool got there, the engagement of every layer is computed once, exactly,
// by geometry::compute_engagement evaluated on that layer's height — so a helix removes material
// depth by depth and a 2.5D program shares one computation for all its layers.

#include <span>
#include <string>
#include <vector>

#include "feedplan/geometry/engagement.hpp"
#include "feedplan/geometry/stock.hpp"
#include "feedplan/geometry/tool_path.hpp"

namespace feedplan::sim {

//! How the stock is cut into layers and how finely the path is sampled.
struct LayerOptions {
  double layer_thickness_mm = 0.25;  //!< axial layer (and force slice) thickness, mm
  double ds_mm = 0.02;               //!< engagement sample spacing along the path, mm
};

//! Axial layers of the stock from the lowest feed-move tip (or the stock bottom, if higher) up to the
//! stock top, each with the engagement of the tool circle along the path on that layer.
class LayeredEngagement {
 public:
  //! Computes the layers for `path` cut by a tool of `tool_radius_mm` on `stock`. Layers whose
  //! engagement cannot differ (no move and no stock face between their heights) share one
  //! computation. Requires a consistent path and positive options (asserted).
  LayeredEngagement(const geometry::ToolPath& path, const geometry::Stock& stock, double tool_radius_mm,
                    const LayerOptions& options = {});

  int layer_count() const { return static_cast<int>(layer_band_.size()); }
  double layer_bottom_mm(int layer) const { return z_base_mm_ + layer * thickness_mm_; }
  double layer_top_mm(int layer) const { return z_base_mm_ + (layer + 1) * thickness_mm_; }
  //! Number of distinct engagement computations (bands of equivalent layers).
  int band_count() const { return static_cast<int>(profiles_.size()); }

  //! A position along the path for the lookups below; keep one per layer band and advance it with s.
  struct Cursor {
    std::size_t sample = 0;
  };
  //! Engaged arcs (immersion angles relative to the feed direction, as in geometry::EngagedInterval)
  //! of `layer` at the sample nearest to arc length `s_mm`. `cursor` must be the caller's cursor for
  //! this layer's band (band_of); s may move forward or backward.
  std::span<const geometry::EngagedInterval> intervals_at(int layer, double s_mm, Cursor& cursor) const;
  int band_of(int layer) const { return layer_band_[layer]; }

  //! Engagement profile of a band (for reports and tests).
  const geometry::EngagementProfile& band_profile(int band) const { return profiles_[band]; }
  //! Collisions and gouges found on any layer (rapids or air moves meeting material).
  const std::vector<std::string>& warnings() const { return warnings_; }

 private:
  double z_base_mm_ = 0.0;
  double thickness_mm_ = 0.0;
  std::vector<int> layer_band_;
  std::vector<geometry::EngagementProfile> profiles_;
  std::vector<std::string> warnings_;
};

}  // namespace feedplan::sim
