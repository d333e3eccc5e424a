// Activations: names (ours and PyTorch's) round-trip, the list is complete, and the values
// are PyTorch's (reference values of torch.nn's default modules).

#include "policy/activation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

namespace upkie_rl {
namespace {

const Activation kAll[] = {Activation::kReLU,      Activation::kTanh,     Activation::kELU,
                           Activation::kLeakyReLU, Activation::kSiLU,     Activation::kGELU,
                           Activation::kSigmoid,   Activation::kSoftplus, Activation::kSELU};

TEST(Activation, NamesRoundTripAndPyTorchNamesAreRead) {
  for (const Activation activation : kAll) {
    EXPECT_EQ(parse_activation(activation_name(activation)), activation);
  }
  EXPECT_EQ(parse_activation("LeakyReLU"), Activation::kLeakyReLU);
  EXPECT_EQ(parse_activation("GELU"), Activation::kGELU);
  EXPECT_THROW(parse_activation("Hardswish"), std::invalid_argument);
}

TEST(Activation, TheListHoldsEveryOneOnceAndNamesThemAll) {
  const std::vector<Activation> listed = all_activations();
  ASSERT_EQ(listed.size(), std::size(kAll));
  const std::string names = activation_names();
  for (std::size_t i = 0; i < listed.size(); ++i) {
    EXPECT_EQ(listed[i], kAll[i]);
    EXPECT_NE(names.find(activation_name(kAll[i])), std::string::npos) << names;
  }
  EXPECT_EQ(activation_torchscript(Activation::kELU, "x"), "torch.elu(x)");
  try {
    parse_activation("swish");
    FAIL() << "swish parsed";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find(names), std::string::npos) << error.what();
  }
}

TEST(Activation, ValuesArePyTorchs) {
  struct Case {
    Activation activation;
    double input;
    double expected;  // torch.nn.<Module>()(torch.tensor(input, dtype=torch.float64))
  };
  const Case cases[] = {{Activation::kReLU, -1.0, 0.0},
                        {Activation::kTanh, 0.5, 0.46211715726000974},
                        {Activation::kELU, -1.0, -0.6321205588285577},
                        {Activation::kLeakyReLU, -2.0, -0.02},
                        {Activation::kSiLU, 1.0, 0.7310585786300049},
                        {Activation::kGELU, 1.0, 0.8413447460685429},
                        {Activation::kSigmoid, 0.0, 0.5},
                        {Activation::kSoftplus, 0.0, std::log(2.0)},
                        {Activation::kSoftplus, 30.0, 30.0},
                        {Activation::kSELU, -1.0, -1.1113307378125625},
                        {Activation::kSELU, 2.0, 2.101401974710961}};
  for (const Case& c : cases) {
    EXPECT_NEAR(apply_activation(c.activation, c.input), c.expected, 1e-12)
        << activation_name(c.activation) << "(" << c.input << ")";
  }
}

}  // namespace
}  // namespace upkie_rl
