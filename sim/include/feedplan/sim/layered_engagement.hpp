#pragma once
// The stock as the virtual machine sees it: axial layers, each with the engaged arcs of the tool
// circle along the whole path. Because the material the tool meets at a point of the path does not
// depend on how fast the tool got there, the engagement of every layer is computed once, exactly,
// by geometry::compute_engagement evaluated on that layer's height — so a helix removes material
// depth by depth and a 2.5D program shares one computation for all its layers.
//
// A helical entry makes every layer it crosses different, but only until moves below them have
// re-cut its track (a bore's flat bottom circle): from there on a layer's engagement is the lowest
// layer's, and only the stretch before is computed for it (track_cover.hpp). A 10 mm deep pocket
// bored with a 1 mm pitch then costs about one engagement of the path, not two hundred. Re-cut means
// on the same track within `recut_tolerance_mm`: an arc's track is re-cut by arcs whose tracks lie
// within it of the arc's circle, whatever their own centres. Exact, by default; a G-code program
// read back from 3 decimals needs about 1.4 µm, the rounding of its points (its bottom circle's
// pieces are written up to 0.7 µm off the helix's circle).
//
// Memory: every band samples the path at the same places, so the places are kept once; a sample's
// arcs are kept once for all the bands in a row that have the same ones (16 bytes per arc, 6 bytes
// per sample and band).

#include <cstddef>
#include <cstdint>
#include <functional>
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
  //! Share a layer's engagement with the lowest layer's once moves below both have re-cut every move
  //! between them (false: every band computed along the whole path — for tests of the sharing).
  bool share_recut_layers = true;
  //! How far a re-cutting track may lie from the one it re-cuts, mm (see above).
  double recut_tolerance_mm = 1e-9;
  //! Called after each band with the path length sampled so far and in all, over all bands, mm (the
  //! work of the engagement); may be empty.
  std::function<void(double done_mm, double total_mm)> progress;
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
  //! Number of bands of equivalent layers (distinct engagements).
  int band_count() const { return static_cast<int>(bands_.size()); }
  //! Engagement samples computed over all bands (one band along the whole path counts its samples).
  std::size_t samples_computed() const { return samples_computed_; }

  //! A position along the path for the lookups below: the last sample found. Every band samples the
  //! path at the same places, so one cursor serves all layers.
  struct Cursor {
    std::size_t sample = 0;
  };
  //! The sample nearest to arc length `s_mm`, searched from `cursor` (s may move forward or backward;
  //! the search is short when it moves little); 0 when there are no samples.
  std::size_t sample_at(double s_mm, Cursor& cursor) const;
  //! Engaged arcs (immersion angles relative to the feed direction, as in geometry::EngagedInterval)
  //! of the layers of `band` at `sample` (from sample_at); empty when there are no samples.
  std::span<const geometry::EngagedInterval> band_intervals(int band, std::size_t sample) const;
  //! Engaged arcs of `layer` at the sample nearest to arc length `s_mm` (sample_at, then band_intervals).
  std::span<const geometry::EngagedInterval> intervals_at(int layer, double s_mm, Cursor& cursor) const;
  int band_of(int layer) const { return layer_band_[layer]; }

  //! Collisions and gouges found on any layer (rapids or air moves meeting material).
  const std::vector<std::string>& warnings() const { return warnings_; }

 private:
  // The arcs of one band at the samples it computed (its first `size()` samples, where s_mm_ says);
  // the later ones are the lowest band's.
  struct Band {
    std::vector<std::uint32_t> interval_begin;  // into intervals_
    std::vector<std::uint16_t> interval_count;
    std::size_t size() const { return interval_begin.size(); }
  };
  void add_band(const geometry::EngagementProfile& profile, std::size_t sample_count);
  std::span<const geometry::EngagedInterval> sample_intervals(const Band& band, std::size_t i) const;

  double z_base_mm_ = 0.0;
  double thickness_mm_ = 0.0;
  std::vector<int> layer_band_;
  std::vector<double> s_mm_;                          // the samples' places along the path, all bands
  std::vector<geometry::EngagedInterval> intervals_;  // the arcs of all bands
  std::vector<Band> bands_;
  std::vector<std::string> warnings_;
  std::size_t samples_computed_ = 0;
};

}  // namespace feedplan::sim
