// A hairstyle session as lapis.HairSession holds it: the document and its head.
#pragma once

#include "lapis/hair_sketch/document.h"
#include "lapis/hair_sketch/head.h"

namespace lapis::python {

struct Session {
  hair_sketch::Hairstyle style;
  hair_sketch::Head head;
};

}  // namespace lapis::python
