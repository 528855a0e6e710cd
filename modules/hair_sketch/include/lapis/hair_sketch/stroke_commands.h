// Strokes to document commands (thesis §4.5): the sketch interpretation of sketch.h applied
// to a document, recording the stroke with the command so that a session can be replayed
// from its input alone. A rejected stroke throws StrokeRejected and changes nothing.
#pragma once

#include "lapis/hair_field/grid.h"
#include "lapis/hair_sketch/document.h"
#include "lapis/hair_sketch/head.h"

namespace lapis::hair_sketch {

// The command a stroke means for the document's current state (not executed). Throws
// StrokeRejected for an uninterpretable stroke, a missing or wrong-kind target, or the
// wrong number of strokes for the action.
Command command_from_stroke(const Hairstyle& style, const RecordedStroke& stroke, const Head& head,
                            const hair_field::Grid& grid);

// command_from_stroke, then Document::execute.
void apply_stroke(Document& document, const RecordedStroke& stroke, const Head& head, const hair_field::Grid& grid);

// The session's settings, camera and strand details with the primitives rebuilt from its recorded strokes
// alone (grid from the settings). Throws StrokeRejected naming the stroke's index when one
// is rejected: a recorded session only holds strokes that were accepted.
Hairstyle replay_strokes(const Hairstyle& session, const Head& head);

}  // namespace lapis::hair_sketch
