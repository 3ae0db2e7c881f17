// The model file's contacts section (docs/model-format.md, "contacts"): read, written and read back
// unchanged, and each kind of bad entry refused at its line.
#include <gtest/gtest.h>

#include "sinew/core/error.hpp"
#include "sinew/io/model_file.hpp"
#include "support/error_assertions.hpp"
#include "support/standing_model.hpp"

namespace sinew {
namespace {

TEST(ModelContacts, ReadAsWrittenInTheFile) {
    const Model model = test::makeStandingModel();
    ASSERT_EQ(model.getContacts().size(), 2u);
    const Contact& right = model.getContacts()[0];
    EXPECT_EQ(right.name, "foot_r");
    EXPECT_EQ(right.link, model.findLinkIndex("leg_r"));
    EXPECT_EQ(right.friction, 0.8);
    ASSERT_EQ(right.sole_B.size(), 4u);
    EXPECT_EQ(right.sole_B[1], Eigen::Vector3d(0.15, -0.04, -0.9));
}

TEST(ModelContacts, WriteThenReadGivesTheSameContacts) {
    const Model model = test::makeStandingModel();
    const std::string text = writeModelText(model);
    const Model again = readModelText(text, "again.yaml");
    ASSERT_EQ(again.getContacts().size(), model.getContacts().size());
    for (std::size_t c = 0; c < model.getContacts().size(); ++c) {
        const Contact& a = model.getContacts()[c];
        const Contact& b = again.getContacts()[c];
        EXPECT_EQ(a.name, b.name);
        EXPECT_EQ(a.link, b.link);
        EXPECT_EQ(a.friction, b.friction);
        EXPECT_EQ(a.sole_B, b.sole_B);
    }
    EXPECT_EQ(writeModelText(again), text);
}

TEST(ModelContacts, AModelWithoutFeetWritesNoContactsSection) {
    const Model model = readModelText(test::standingModelText(false), "plain.yaml");
    EXPECT_TRUE(model.getContacts().empty());
    EXPECT_EQ(writeModelText(model).find("contacts"), std::string::npos);
}

// The standing model's text with its contacts replaced by `entry`, which then sits at line `line`.
::testing::AssertionResult rejects(const std::string& entry, const std::vector<std::string>& words) {
    const std::string text = test::standingModelText(false) + "contacts:\n" + entry + "\n";
    int line = 0;
    for (const char c : text) line += c == '\n';
    return test::throwsErrorAt<ModelError>([&] { readModelText(text, "bad.yaml"); },
                                           "bad.yaml:" + std::to_string(line) + ": ", words, text);
}

TEST(ModelContacts, BadEntriesAreRefusedAtTheirLine) {
    EXPECT_TRUE(rejects("  - {name: f, link: shin, sole: [[0, 0, 0]]}", {"contact 'f'", "unknown link 'shin'"}));
    EXPECT_TRUE(rejects("  - {name: f, link: ground, sole: [[0, 0, 0]]}", {"contact 'f'", "unknown link 'ground'"}));
    EXPECT_TRUE(rejects("  - {name: f, link: leg_r, sole: []}", {"contact 'f'", "sole"}));
    EXPECT_TRUE(rejects("  - {name: f, link: leg_r, sole: [[0, 0]]}", {"sole"}));
    EXPECT_TRUE(rejects("  - {name: f, link: leg_r, friction: -1, sole: [[0, 0, 0]]}", {"contact 'f'", "friction"}));
    EXPECT_TRUE(rejects("  - {name: f, link: leg_r, sole: [[0, 0, 0]], heel: 1}", {"heel"}));
    EXPECT_TRUE(rejects("  - {link: leg_r, sole: [[0, 0, 0]]}", {"name"}));
    EXPECT_TRUE(rejects("  - {name: f, link: leg_r, sole: [[0, 0, 0]]}\n  - {name: f, link: leg_l, sole: [[0, 0, 0]]}",
                        {"duplicate contact name 'f'"}));
}

}  // namespace
}  // namespace sinew
