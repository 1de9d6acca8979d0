// `radchain validate` (in the imaging module): the closed-loop checks, render and measure against the model.
#include "imaging_common.hpp"
#include "../overrides.hpp"

#include "radchain/imaging/render.hpp"
#include "radchain/imaging/render_request.hpp"

#include <fmt/format.h>

#include <cmath>
#include <utility>

namespace radchain::cli {

using namespace radchain::render;

int validate_command(const ValidateCommand& c) {
  const Params v = validated_options(validate_option_schema(), c.values, "radchain validate");
  const double max_z = v.get("--max-z");
  const int size = static_cast<int>(v.integer("--size"));
  Chain chain = load_sensor_of(c.sensor);
  const Report report = chain.run();
  const SensorView view = sensor_view(chain, report);
  bool ok = true;
  // The frame options every point-target check starts from: the geometry options and the pedestal.
  auto point_frame = [&] {
    SpaceFrameOptions frame;
    apply_frame_geometry(frame, v);
    frame.offset_dn = v.get("--offset");
    return frame;
  };
  auto matched_filter_options = [&] {
    StreakCheckOptions o;
    o.trials = v.integer("--trials");
    o.seed = c.seed;
    return o;
  };
  auto verdict = [&](bool passed) {
    ok = ok && passed;
    return passed ? "ok  " : "FAIL";
  };
  auto space_flat_field = [&](const SpaceFrameOptions& frame) {
    const FlatFieldCheck flat = check_space_flat_field(chain, report, frame, size, c.seed);
    fmt::print("  {} flat field: measured SNR {:.5g} ± {:.2g}, budget with the ADC {:.5g}, chain {:.5g}; noise {:.5g} vs {:.5g} e-\n",
               verdict(flat.passed(max_z)), flat.measured_snr, flat.snr_sigma, flat.predicted_snr, flat.chain_snr,
               flat.measured_noise, flat.predicted_noise);
  };
  if (view.image == SensorImage::point_frame && view.point_check == PointCheck::streak) {
    // A moving target: PSF-weighted photometry along its streak (a square detection window does not apply).
    const StreakCheck check = check_streak(chain, report, point_frame(), matched_filter_options());
    fmt::print("{}: streak of {:.4g} pixels at the limiting magnitude {:.4f} (S = {:.4g} e-, n_eff {:.4g} px, still {:.4g} px; "
               "{} frames)\n",
               c.sensor.sensor, check.streak_px, check.magnitude, check.signal_electrons, check.neff, check.static_neff, check.trials);
    for (const auto& [name, snr] : {std::pair{"streak", check.streak}, std::pair{"still ", check.still}})
      fmt::print("  {} {} SNR measured {:.4f} ± {:.2g}, renderer's law {:.4f} (z = {:+.2f})\n", verdict(std::abs(snr.z()) <= max_z),
                 name, snr.measured, snr.sigma, snr.predicted, snr.z());
    fmt::print("  chain SNR {:.4f} (S/√(S + n_eff v), SMTN-002)\n", check.chain_snr);
    fmt::print("  {} SNR loss 2.5 lg(SNR_still/SNR_streak) measured {:.4f} ± {:.2g} mag, renderer's law {:.4f}; chain's trailing "
               "loss at constant SNR (background-limited) {:.4f}\n",
               verdict(std::abs(check.measured_snr_loss() - check.predicted_snr_loss()) <= max_z * check.snr_loss_sigma()),
               check.measured_snr_loss(), check.snr_loss_sigma(), check.predicted_snr_loss(), check.chain_trailing_loss);
  } else if (view.image == SensorImage::point_frame && view.point_check == PointCheck::psf_photometry) {
    // PSF-weighted photometry of a still target: the matched filter, not a square window.
    const SpaceFrameOptions frame = point_frame();
    const PsfPhotometryCheck check = check_psf_photometry(chain, report, frame, matched_filter_options());
    fmt::print("{}: PSF-weighted photometry at the limiting magnitude {:.4f} (S = {:.4g} e-, n_eff {:.4g} px rendered, {:.4g} "
               "chain; {} frames)\n",
               c.sensor.sensor, check.magnitude, check.signal_electrons, check.neff, check.chain_neff, check.trials);
    fmt::print("  {} matched-filter SNR measured {:.4f} ± {:.2g}, renderer's law {:.4f} (z = {:+.2f})\n",
               verdict(std::abs(check.still.z()) <= max_z), check.still.measured, check.still.sigma, check.still.predicted,
               check.still.z());
    if (check.fixed_pattern)
      fmt::print("  --   S/√(S + n_eff v) on the frame {:.4f} vs chain SNR {:.4f}: not compared, the chain counts DSNU/PRNU, "
                 "which point-target frames do not render\n",
                 check.chain_form_snr, check.chain_snr);
    else
      fmt::print("  {} S/√(S + n_eff v) on the frame {:.4f} vs chain SNR {:.4f} ({:+.3f} %, within {:g} %); the matched "
                 "filter's law differs by the source's own shot noise ({:+.2f} %)\n",
                 verdict(check.chain_agrees()), check.chain_form_snr, check.chain_snr,
                 100 * (check.chain_form_snr / check.chain_snr - 1), 100 * check.tolerance,
                 100 * (check.still.predicted / check.chain_form_snr - 1));
    space_flat_field(frame);
  } else if (view.image == SensorImage::point_frame) {
    const SpaceFrameOptions frame = point_frame();
    DetectionCheckOptions d;
    d.trials = v.integer("--trials");
    d.seed = c.seed;
    d.threshold_sigma = v.get("--threshold");
    const DetectionCheck check = check_detection(chain, report, frame, d);
    fmt::print("{}: detection at the limiting magnitude {:.4f} (S = {:.4g} e-, n = {:.4g} e-, σ₀ = {:.4g} e-, SNR = {:.4g}, "
               "window {}×{}, threshold γ = {:.4g} σ₀, at a level between two window sums {:.4g} σ₀)\n",
               c.sensor.sensor, check.magnitude, check.signal_electrons, check.noise_electrons, check.noise_only_electrons, check.snr,
               check.window, check.window, check.threshold_sigma, check.effective_threshold_sigma);
    fmt::print("  {} rendered window signal {:.5g} e- vs chain {:.5g} e-\n",
               verdict(std::abs(check.rendered_signal_electrons / check.signal_electrons - 1.0) <= 0.01),
               check.rendered_signal_electrons, check.signal_electrons);
    for (const auto& [name, rate] : {std::pair{"P_d ", check.detection}, std::pair{"P_fa", check.false_alarm}})
      fmt::print("  {} {} measured {:.6f} ({} of {}), Gaussian criterion {:.6f} (z = {:+.2f}), renderer's exact law {:.6f} (z = {:+.2f})\n",
                 verdict(std::abs(rate.z_predicted()) <= max_z), name, rate.measured, rate.count, rate.trials, rate.predicted,
                 rate.z_predicted(), rate.exact, rate.z_exact());
    space_flat_field(frame);
  } else {
    EarthSceneOptions scene;
    scene.offset_dn = v.get("--offset");
    const EdgeCheck edge = check_edge_mtf(chain, report, scene);
    fmt::print("{}: slanted edge at {:.2f}°: MTF at Nyquist measured {:.4f}, model {:.4f}; max deviation up to Nyquist {:.2f} %\n",
               c.sensor.sensor, edge.angle_deg, edge.mtf_at_nyquist_measured, edge.mtf_at_nyquist_model, 100 * edge.max_relative_error);
    fmt::print("  {} edge MTF within {:.0f} %\n", verdict(edge.passed()), 100 * edge.tolerance);
    const FlatFieldCheck flat = check_earth_flat_field(chain, report, scene, size, c.seed);
    fmt::print("  {} {} {:.5g} ± {:.2g}, budget with the ADC {:.5g}, chain {:.5g}; noise {:.4g} vs {:.4g} {}\n",
               verdict(flat.passed(max_z)), flat.measured_label, flat.measured_snr, flat.snr_sigma, flat.predicted_snr,
               flat.chain_snr, flat.measured_noise, flat.predicted_noise, flat.noise_unit);
  }
  if (!ok && view.image == SensorImage::point_frame && view.clipped_at_zero(v.get("--offset")))
    fmt::print("  note: the rendered frames have no ADC pedestal (--offset 0) and their dark level is within 3σ of 0 DN: "
               "noise below 0 DN is clipped, which the laws above do not model and which may contribute; rerun with "
               "--offset (e.g. 100)\n");
  return ok ? 0 : 1;
}

}  // namespace radchain::cli
