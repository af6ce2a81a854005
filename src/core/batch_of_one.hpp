// A batch kernel's single-element evaluate() and energy() (element.hpp, Kernel::Batch) as
// its batch path run on a block of one element: the kernel's physics is written once, in
// its Batch, and the finite-difference checks of evaluate() check the code the block runs.
// The batch of one is kept per thread and kernel type and given the kernel anew at each
// call (Batch::assign, which then allocates nothing).
#pragma once

#include <Eigen/Dense>
#include <vector>

#include "core/element.hpp"

namespace tirefe {

namespace detail {
/// This thread's batch of one element, holding 'kernel'.
template <class Kernel>
typename Kernel::Batch& batch_of_one(const Kernel& kernel) {
  thread_local std::vector<Kernel> one(1, kernel);
  thread_local typename Kernel::Batch batch(one);
  one[0] = kernel;
  batch.assign(one);
  return batch;
}
}  // namespace detail

/// kernel.evaluate(local, context, ...) through Kernel::Batch; the tangent when it is not null.
template <class Kernel>
void evaluate_as_batch(const Kernel& kernel, const LocalState<Kernel::kDofs>& local, const EvaluationContext& context,
                       typename Kernel::Vector& residual, typename Kernel::Matrix* tangent) {
  constexpr KernelTraits traits = Kernel::traits();
  typename Kernel::Batch& batch = detail::batch_of_one(kernel);
  // The values the block's gather gives the batch: the rates only for a kernel that reads them.
  const BlockValues values{1, local.displacement.data(), traits.reads_velocity ? local.velocity.data() : nullptr,
                           traits.reads_acceleration ? local.acceleration.data() : nullptr};
  batch.evaluate(values, context, tangent != nullptr);
  // One element: local DOF k at [k], row-major tangent entry k at [k].
  residual = Eigen::Map<const typename Kernel::Vector>(batch.residual());
  if (tangent) *tangent = Eigen::Map<const typename Kernel::Matrix>(batch.tangent());
}

/// kernel.energy(local, ...) through Kernel::Batch::energy (which reads no accelerations).
template <class Kernel>
ElementEnergy batch_energy_of_one(const Kernel& kernel, const LocalState<Kernel::kDofs>& local) {
  constexpr KernelTraits traits = Kernel::traits();
  return detail::batch_of_one(kernel).energy(
      BlockValues{1, local.displacement.data(), traits.reads_velocity ? local.velocity.data() : nullptr, nullptr});
}

}  // namespace tirefe
