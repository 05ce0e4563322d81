// SPDX-License-Identifier: MIT
// Face guidance in the sampling chain (runtime/sampling/sampler.h): after the grammar mask and
// surface guidance, each legal between-layer id (B) is judged by the faces it would close, so
// the model connects vertices across the input's surface rather than through or across it.
#pragma once
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "runtime/sampling/face_guide.h"
#include "runtime/sampling/sampler.h"

namespace silk {

class Grammar;
struct GenerationStats;

// Before the logits. A B id (s, case) joins the vertex being written to the previous layer's
// columns of its segment; it closes every triangle of the edge graph through a new edge: with
// two of those columns that are neighbours in the previous layer (either one may come from the
// row's earlier B ids), and with an earlier vertex of its own layer it is linked to whose row
// holds the column. Its score is the worst of those faces, of its new edges alone (FaceGuide),
// and of each such face's folds (FaceGuide::FoldScore) onto every other triangle of the edge
// graph on one of its three edges (the layer before the previous one included): the surface
// must not double back over itself, whichever way the faces will be wound. Positions (K, O) are
// judged by the faces and edges they fix. S and X ids (in-layer links to later rows) are judged by
// the later rows they link: each must keep a position whose faces with all its linked rows pass.
// Hard: ids scoring above 1 are removed; when none of the step's own kind passes, a row that has
// its B may end (K, U or E stay), otherwise the ones within 25 % of the best score are kept
// (stats->face_fallbacks; SamplerCandidates::face). Soft: nothing is removed; the step's logit
// penalties (id, amount), kFaceSoftPenalty per unit past 1, go to SamplerCandidates::penalties for
// MakeFacePenaltyStage. U, E and forced ids are never touched, so the mask never empties. The
// vertex's and the previous layer's parts are computed once per vertex and layer, a later row's
// link score once per vertex and distance; nothing is allocated per id.
std::unique_ptr<SamplerStage> MakeFaceGuideStage(const FaceGuide* guide, FaceGuidance mode, const Grammar* grammar,
                                                 GenerationStats* stats);

// First on the logits, soft form: the step's logits with the penalties subtracted (float, as the
// reference loop does) in a buffer of the stage's own; no penalties: the logits untouched.
std::unique_ptr<SamplerStage> MakeFacePenaltyStage();

}  // namespace silk
