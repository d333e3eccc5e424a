#include "spine/dictionary.hpp"

#include <gtest/gtest.h>

#include "message_builder.hpp"
#include "spine/spine_error.hpp"

namespace upkie_rl {
namespace {

using testing::MessageBuilder;
using testing::servo_field;

void expect_error_containing(Dictionary& dictionary, MessageBuilder& message,
                             const std::string& fragment) {
  try {
    dictionary.update(message.object().get());
    FAIL() << "no error, expected one containing '" << fragment << "'";
  } catch (const SpineError& error) {
    EXPECT_NE(std::string(error.what()).find(fragment), std::string::npos) << error.what();
  }
}

TEST(Dictionary, MergeKeepsAbsentKeys) {
  Dictionary dictionary;
  MessageBuilder first;
  first.map(1).key("servo").map(2);
  first.key("left_hip").map(2).key("position").real(0.5).key("velocity").real(1.0);
  first.key("right_hip").map(1).key("position").real(-0.5);
  dictionary.update(first.object().get());
  MessageBuilder second = servo_field("left_hip", "position");
  second.real(0.25);
  dictionary.update(second.object().get());
  const Dictionary& servo = dictionary.at("servo");
  EXPECT_DOUBLE_EQ(servo.at("left_hip").at("position").as_number(), 0.25);
  EXPECT_DOUBLE_EQ(servo.at("left_hip").at("velocity").as_number(), 1.0);
  EXPECT_DOUBLE_EQ(servo.at("right_hip").at("position").as_number(), -0.5);
  EXPECT_EQ(servo.size(), 2u);
}

TEST(Dictionary, ArraysAreTypedByLength) {
  Dictionary dictionary;
  MessageBuilder message;
  message.map(5);
  message.key("a").array(2).real(1).real(2);
  message.key("b").array(3).real(1).real(2).real(3);
  message.key("c").array(4).real(1).integer(0).real(0).real(0);
  message.key("d").array(9);
  for (int i = 0; i < 9; ++i) message.real(i);
  message.key("e").array(6);
  for (int i = 0; i < 6; ++i) message.real(i);
  dictionary.update(message.object().get());
  EXPECT_EQ(dictionary.at("a").kind(), Dictionary::Kind::kVector2);
  EXPECT_EQ(dictionary.at("b").kind(), Dictionary::Kind::kVector3);
  EXPECT_EQ(dictionary.at("c").kind(), Dictionary::Kind::kQuaternion);
  EXPECT_EQ(dictionary.at("d").kind(), Dictionary::Kind::kMatrix3);
  EXPECT_EQ(dictionary.at("e").kind(), Dictionary::Kind::kVector);
  EXPECT_DOUBLE_EQ(dictionary.at("d").as_array()[8], 8.0);
  // Same kind, other length: fine for plain vectors.
  MessageBuilder longer;
  longer.map(1).key("e").array(7);
  for (int i = 0; i < 7; ++i) longer.real(-i);
  dictionary.update(longer.object().get());
  EXPECT_EQ(dictionary.at("e").as_array().size(), 7u);
  // vector3 -> quaternion is a type change.
  MessageBuilder changed;
  changed.map(1).key("b").array(4).real(1).real(0).real(0).real(0);
  expect_error_containing(dictionary, changed, "'b' changed type from vector3 to quaternion");
}

TEST(Dictionary, RefusesNil) {
  Dictionary dictionary;
  MessageBuilder message = servo_field("left_wheel", "velocity");
  message.nil();
  expect_error_containing(dictionary, message, "servo.left_wheel.velocity' has a nil value");
}

TEST(Dictionary, RefusesBinaryAndNilInArrays) {
  Dictionary dictionary;
  MessageBuilder binary;
  binary.map(1).key("blob").binary("abc");
  expect_error_containing(dictionary, binary, "binary value");
  MessageBuilder nil_element;
  nil_element.map(1).key("v").array(3).real(1).nil().real(3);
  expect_error_containing(dictionary, nil_element, "arrays must hold numbers");
}

TEST(Dictionary, RefusesTypeChanges) {
  Dictionary dictionary;
  MessageBuilder first = servo_field("left_wheel", "velocity");
  first.real(1.0);
  dictionary.update(first.object().get());
  MessageBuilder as_int = servo_field("left_wheel", "velocity");
  as_int.integer(1);
  expect_error_containing(dictionary, as_int, "changed type from float to int");
  MessageBuilder as_map = servo_field("left_wheel", "velocity");
  as_map.map(0);
  expect_error_containing(dictionary, as_map, "changed type from float to map");
  MessageBuilder servo_as_float;
  servo_as_float.map(1).key("servo").real(2.0);
  expect_error_containing(dictionary, servo_as_float, "'servo' changed type from map to float");
  // float32 and float64 are one type: floats.
  MessageBuilder as_float32 = servo_field("left_wheel", "velocity");
  as_float32.real32(0.5f);
  EXPECT_NO_THROW(dictionary.update(as_float32.object().get()));
  EXPECT_DOUBLE_EQ(dictionary.at("servo").at("left_wheel").at("velocity").as_number(), 0.5);
}

TEST(Dictionary, RefusesNonStringKeysAndNonMapMessages) {
  Dictionary dictionary;
  MessageBuilder int_key;
  int_key.map(1).integer(3).real(1.0);
  expect_error_containing(dictionary, int_key, "keys must be strings");
  MessageBuilder array_root;
  array_root.array(1).real(1.0);
  expect_error_containing(dictionary, array_root, "expected a map");
}

TEST(Dictionary, AccessorsCheckKinds) {
  Dictionary dictionary;
  MessageBuilder message;
  message.map(4).key("flag").boolean(true).key("name").string("upkie").key("count").integer(-3);
  message.key("x").real(1.5);
  dictionary.update(message.object().get());
  EXPECT_TRUE(dictionary.at("flag").as_bool());
  EXPECT_EQ(dictionary.at("name").as_string(), "upkie");
  EXPECT_DOUBLE_EQ(dictionary.at("count").as_number(), -3.0);
  EXPECT_THROW(dictionary.at("x").as_bool(), SpineError);
  EXPECT_THROW(dictionary.at("flag").as_number(), SpineError);
  EXPECT_THROW(dictionary.at("x").as_array(), SpineError);
  EXPECT_THROW(dictionary.at("missing"), SpineError);
  EXPECT_THROW(dictionary.at("x").at("y"), SpineError);
  dictionary.clear();
  EXPECT_FALSE(dictionary.has("x"));
}

}  // namespace
}  // namespace upkie_rl
