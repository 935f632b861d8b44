// The wear profile (docs/wear.md): the contact's load–distance ∫F_n|V_t| dt and frictional heat placed
// along the surface, at the material coordinate of each contact step's ends and of each impact
// (Surface::material_coordinate), binned over the span the contact touched. Of the pass, or of the
// last complete revolutions of a run over many.
#pragma once

#include "pass_observer.hpp"

#include "rotbeam/wear.hpp"

#include <array>

namespace rotbeam {

class WearProfile final : public PassObserver {
public:
  explicit WearProfile(PassContext& context);

  void step(const StepView& v) override;
  void impact(const ImpactView& v) override;
  void contact_start(double t, const Eigen::VectorXd& q, const ContactLoad&, bool) override;
  void contact_end(double, const Eigen::VectorXd&) override { have_last_ = false; }
  void open_revolution(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd) override;
  void close_revolution(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, RevolutionRecord& r) override;
  void finish(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd) override;

private:
  double coordinate(double t, const Eigen::VectorXd& q) const;
  std::vector<WearBin> profile(const WearTrack& track) const;

  PassContext& ctx_;
  double period_, min_span_;
  WearTrack track_;                                      // of the pass, or of the revolution under way
  std::array<WearTrack, kWearRevolutionsKept> kept_;     // the last complete revolutions' (a ring)
  int kept_count_ = 0, kept_next_ = 0;
  double last_ = 0;  // the material coordinate at the last accepted contact point
  bool have_last_ = false;
};

}  // namespace rotbeam
