#pragma once
// sinew's detailed whole-body wire model, derived from a detailed source model (MS-Human-700, imported from
// MJCF) by rules kept in the repository (models/whole_body/rules.yaml), reshaped as the paper designed its
// own model: source bodies grouped into rigid links joined by ball joints, a free root, ball-loop closures
// where anatomy closes a chain, forked muscles meeting at massless virtual links with a tendon beyond, and
// passive ligaments and cartilage placed from landmarks. Every wire is a passive spring-damper (the paper's
// section 4.1 experiment). The rules and the derivation are in docs/whole-body-model.md.
#include <optional>
#include <string>
#include <vector>

#include "sinew/core/model.hpp"
#include "sinew/io/whole_body_rules.hpp"

namespace sinew {

struct WholeBodyBuild {
    Model model;
    // What the reshaping changed that a reader must know: forked units' junctions, wraps turned into via
    // points on forked units, completed masses.
    std::vector<std::string> notes;
};

// `source` at its default pose is the neutral pose; `segmentRatios` is needed when rules.missingMass is set.
WholeBodyBuild buildWholeBodyModel(const Model& source, const WholeBodyRules& rules,
                                   const std::optional<SegmentRatios>& segmentRatios);

}  // namespace sinew
