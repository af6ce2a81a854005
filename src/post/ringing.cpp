#include "post/ringing.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace tirefe::post {

RingingReading read_ringing(const std::vector<double>& times, const std::vector<double>& values, double from, double to,
                            const RingingBand& band) {
  const SignalWindow window = prepare_window(times, values, from, to);
  RingingReading reading;
  reading.samples = window.raw_samples;
  reading.peak_to_peak = window.peak_to_peak;
  reading.spectrum = spectrum_peak(window, band.min_frequency, band.max_frequency);
  bool found = false;
  for (const DampedComponent& component : matrix_pencil(window)) {  // by decreasing energy
    if (component.frequency >= band.min_frequency && component.frequency <= band.max_frequency) {
      reading.pencil = component;
      found = true;
      break;
    }
  }
  if (!found)
    throw std::invalid_argument("no damped sinusoid between " + std::to_string(band.min_frequency) + " and " +
                                std::to_string(band.max_frequency) + " Hz in the window");
  reading.frequency = 0.5 * (reading.spectrum.frequency + reading.pencil.frequency);
  reading.uncertainty = 0.5 * std::abs(reading.spectrum.frequency - reading.pencil.frequency);
  return reading;
}

}  // namespace tirefe::post
