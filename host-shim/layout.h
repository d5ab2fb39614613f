// Layout and page output: the host's presentation of a document (seed 6.1,
// "presentation schema"), set with Pango, drawn with Cairo.
//
//   tree ──Blocks──▶ title · heading · field ("To: …") · paragraph · embedded
//        ──Paginate──▶ pages of placed blocks (A4, points)
//        ──DrawPage──▶ Cairo: PDF pages, PNG pages
//
// The schema is fixed and small: TITLE and HEADING elements are headings; a
// leaf element outside TEXT/PARAGRAPH (TO, FROM, SUBJECT) is a labelled
// field; TEXT and PARAGRAPH texts are body paragraphs (runs of whitespace
// collapse, a blank line starts a new paragraph); an embedded subdocument is
// a region of its presentation's desired size with a caption under it.
#pragma once

#include <cairo.h>

#include <string>
#include <vector>

#include "host-shim/host_document.h"

namespace asgard::host {

struct Block {
  enum Kind { kTitle, kHeading, kField, kParagraph, kEmbedded };
  Kind kind = kParagraph;
  std::string label;  // kField
  std::string text;
  int item = -1;  // kEmbedded: index into HostDocument::items()
};

std::vector<Block> Blocks(const HostDocument& doc);

struct PageStyle {
  double width = 595.28, height = 841.89;  // A4, points
  double margin = 64;
};

struct Placed {
  Block block;
  double x = 0, y = 0, w = 0, h = 0;  // points; for kEmbedded the picture box
};
struct Page {
  std::vector<Placed> items;
};

std::vector<Page> Paginate(const std::vector<Block>& blocks, const HostDocument& doc,
                           const PageStyle& style = {});

// What an embedded region shows: a picture (may be empty) and a caption.
struct RegionContent {
  Picture picture;
  std::string caption;
};

void DrawPage(cairo_t* cr, const Page& page, const std::vector<RegionContent>& regions,
              const PageStyle& style = {});

// Whole outputs; false with `error` on failure (nothing is left half-written).
bool WritePdf(const std::string& path, const std::vector<Page>& pages,
              const std::vector<RegionContent>& regions, std::string* error,
              const PageStyle& style = {});
// One PNG per page: PATH, then PATH with -2, -3 … before the extension.
bool WritePngPages(const std::string& path, const std::vector<Page>& pages,
                   const std::vector<RegionContent>& regions, double dpi,
                   std::vector<std::string>* written, std::string* error,
                   const PageStyle& style = {});

// One page as a PNG at `dpi`: as WritePngPages draws it (empty with
// `error` on failure).
std::string PagePng(const Page& page, const std::vector<RegionContent>& regions, double dpi,
                    std::string* error, const PageStyle& style = {});

// One line of a page's text as DrawPage sets it, in points: its box (the
// line's logical extents), the baseline, the font, and the line's text
// (tabs as spaces, no line break).  For a text layer over the page's
// picture, where the text can be selected, copied and found.
struct TextLine {
  double x = 0, y = 0, w = 0, h = 0, baseline = 0;
  double size = 0;     // points
  std::string family;  // e.g. "DejaVu Serif"
  bool bold = false;
  std::string text;
};
std::vector<TextLine> PageLines(const Page& page);

// The page boxes as JSON (for tests and tools): pages, blocks, regions.
std::string LayoutJson(const std::vector<Page>& pages, const PageStyle& style = {});

}  // namespace asgard::host
