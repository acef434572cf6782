// Fits of the navigation noise models that docs/simulator.md ("Navigation noise from the real
// logs") uses: a contaminated normal for heavy-tailed white noise and a two-state hidden Markov
// (Gilbert-Elliott) model for bursty DVL dropouts. Pure numerics on already-extracted samples.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace msislab {

/// Isotropic 2-D white noise e = sigma n, n ~ N(0, I), where sigma is core_sigma or, with
/// probability outlier_fraction (independently per sample, both axes at once), outlier_sigma.
struct ContaminatedNormal {
  double core_sigma = 0.0;        ///< per axis, units of the data
  double outlier_fraction = 0.0;  ///< probability that a sample is an outlier, [0, 1]
  double outlier_sigma = 0.0;     ///< per axis, >= core_sigma
  int iterations = 0;             ///< EM iterations run
};

/// Maximum (composite) likelihood fit of a ContaminatedNormal to the first differences
/// d_k = e_{k+1} - e_k of white noise on a smooth signal, by EM with the sample noises e as the
/// latent variables. d_k is a 4-component mixture over which of its two samples are outliers,
/// with variance v_i + v_j per axis; consecutive differences share a sample, so the likelihood
/// treats them as independent (consistent, not efficient). Needs at least 10 differences.
ContaminatedNormal fit_contaminated_normal(const std::vector<Eigen::Vector2d>& differences);

/// Bursty loss of a binary signal: a hidden clear/degraded state that switches as a Markov chain
/// and a per-sample loss probability in each state (the Gilbert-Elliott channel).
struct GilbertElliott {
  double clear_loss_probability = 0.0;     ///< per sample, in the clear state
  double degraded_loss_probability = 0.0;  ///< per sample, in the degraded state (>= clear)
  double degraded_fraction = 0.0;          ///< long-run fraction of samples in the degraded state
  double degraded_mean_samples = 0.0;      ///< mean length of a degraded period, samples
  double log_likelihood = 0.0;             ///< of the sequence under the fit, natural log
  int iterations = 0;                      ///< Baum-Welch iterations run
};

/// Baum-Welch (EM) fit of a GilbertElliott model to a sequence of per-sample losses (true = lost).
/// Needs at least one loss and one non-loss.
GilbertElliott fit_gilbert_elliott(const std::vector<bool>& lost);

}  // namespace msislab
