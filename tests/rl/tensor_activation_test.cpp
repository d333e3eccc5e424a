// The trainer's tensor activations are policy/activation.cpp's (the deployed and exported
// policies' definitions), in and out of place.

#include "rl/ppo/tensor_activation.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace upkie_rl {
namespace {

TEST(TensorActivation, SameValuesAsTheScalarDefinitionInAndOutOfPlace) {
  // Both signs, zero, and both sides of softplus's threshold at 20.
  const torch::Tensor inputs = torch::linspace(-25.0, 25.0, 1001);
  for (const Activation activation : all_activations()) {
    SCOPED_TRACE(activation_name(activation));
    const torch::Tensor outputs = activate(activation, inputs);
    torch::Tensor in_place = inputs.clone();
    const void* storage = in_place.data_ptr();
    activate_in_place(activation, in_place);
    EXPECT_EQ(in_place.data_ptr(), storage);
    EXPECT_TRUE(torch::equal(in_place, outputs));
    for (std::int64_t i = 0; i < inputs.numel(); ++i) {
      const double x = inputs[i].item<float>();
      const double expected = apply_activation(activation, x);
      EXPECT_NEAR(outputs[i].item<float>(), expected, 2e-6 * std::max(1.0, std::abs(expected)))
          << "x = " << x;
    }
  }
}

}  // namespace
}  // namespace upkie_rl
