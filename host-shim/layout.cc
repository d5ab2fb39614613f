// Pango layout and Cairo pages.
//
// Design: every text block is measured with a PangoLayout made from one
// font-map context at 72 dpi with hinted metrics off, so a block has the same
// size in points on every device (PDF, PNG at any resolution) and pagination
// is done once.  A paragraph taller than a page is cut at line boundaries
// into pieces that each fit a page; other blocks never split, and one taller
// than a page is placed alone on its page.  Embedded regions
// are scaled down to the text width when their desired size is wider.
#include "host-shim/layout.h"

#include <cairo-pdf.h>
#include <pango/pangocairo.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <memory>
#include <sstream>

#include "formats/document/file.h"

namespace asgard::host {

namespace {

using document::Node;
using document::NodeKind;

constexpr double kCaptionGap = 4, kCaptionHeight = 22, kGap = 10;

std::string Collapse(const std::string& s) {
  std::string out;
  bool space = false;
  for (char c : s) {
    if (c == ' ' || c == '\t' || c == '\n' || c == '\r') {
      space = !out.empty();
    } else {
      if (space) out += ' ';
      space = false;
      out += c;
    }
  }
  return out;
}

// Splits at blank lines, collapses the rest.
std::vector<std::string> Paragraphs(const std::string& text) {
  std::vector<std::string> out;
  std::string current, line;
  std::istringstream in(text);
  while (std::getline(in, line)) {
    if (Collapse(line).empty()) {
      if (!Collapse(current).empty()) out.push_back(Collapse(current));
      current.clear();
    } else {
      current += line + "\n";
    }
  }
  if (!Collapse(current).empty()) out.push_back(Collapse(current));
  return out;
}

std::string Label(const std::string& tag) {
  std::string s;
  for (size_t i = 0; i < tag.size(); ++i)
    s += static_cast<char>(i ? std::tolower(static_cast<unsigned char>(tag[i])) : tag[i]);
  for (char& c : s)
    if (c == '_') c = ' ';
  return s;
}

std::string Texts(const Node& n) {
  std::string s;
  for (const Node& c : n.children) {
    if (c.kind == NodeKind::kText) s += (s.empty() ? "" : "\n\n") + c.Text();
    if (c.kind == NodeKind::kElement && !c.IsSubdocument())
      s += (s.empty() ? "" : "\n\n") + Texts(c);
  }
  return s;
}

bool Leaf(const Node& n) {
  for (const Node& c : n.children)
    if (c.kind == NodeKind::kElement || c.kind == NodeKind::kHeader) return false;
  return true;
}

void Walk(const HostDocument& doc, const std::vector<Node>& nodes, std::vector<size_t>& path,
          bool in_paragraph, std::vector<Block>& out) {
  for (size_t i = 0; i < nodes.size(); ++i) {
    const Node& n = nodes[i];
    path.push_back(i);
    if (const Embedded* e = doc.ItemAt(path)) {
      Block b;
      b.kind = Block::kEmbedded;
      b.item = e->index - 1;
      out.push_back(b);
    } else if (n.kind == NodeKind::kText && in_paragraph) {
      for (const auto& p : Paragraphs(n.Text())) out.push_back({Block::kParagraph, "", p});
    } else if (n.kind == NodeKind::kElement && n.name != "POSTER") {
      if (n.name == "TITLE" || n.name == "HEADING") {
        out.push_back(
            {n.name == "TITLE" ? Block::kTitle : Block::kHeading, "", Collapse(Texts(n))});
      } else if (n.name == "TEXT" || n.name == "PARAGRAPH" || n.name == "P" || n.IsSubdocument()) {
        Walk(doc, n.children, path, true, out);
      } else if (Leaf(n) && !in_paragraph) {
        out.push_back({Block::kField, Label(n.name), Collapse(Texts(n))});
      } else {
        Walk(doc, n.children, path, in_paragraph, out);
      }
    }
    path.pop_back();
  }
}

struct Fonts {
  PangoFontMap* map = pango_cairo_font_map_get_default();
  PangoContext* context = nullptr;
  Fonts() {
    context = pango_font_map_create_context(map);
    pango_cairo_context_set_resolution(context, 72);
    cairo_font_options_t* o = cairo_font_options_create();
    cairo_font_options_set_hint_metrics(o, CAIRO_HINT_METRICS_OFF);
    cairo_font_options_set_hint_style(o, CAIRO_HINT_STYLE_NONE);
    pango_cairo_context_set_font_options(context, o);
    cairo_font_options_destroy(o);
  }
  ~Fonts() { g_object_unref(context); }
};

Fonts& SharedFonts() {
  static Fonts fonts;
  return fonts;
}

// Text Pango can show: invalid UTF-8 and NUL bytes become U+FFFD (Pango
// drops a whole text that is not valid UTF-8, and a NUL would end it).
std::string Showable(const std::string& text) {
  std::string s = text;
  for (size_t i = 0; (i = s.find('\0', i)) != std::string::npos; i += 3)
    s.replace(i, 1, "\xef\xbf\xbd");
  if (g_utf8_validate(s.data(), static_cast<gssize>(s.size()), nullptr)) return s;
  gchar* valid = g_utf8_make_valid(s.data(), static_cast<gssize>(s.size()));
  std::string out(valid);
  g_free(valid);
  return out;
}

// A layout for a text block, `width` points wide.  Caller unrefs.
PangoLayout* MakeLayout(const Block& b, double width) {
  PangoLayout* layout = pango_layout_new(SharedFonts().context);
  const char* font = b.kind == Block::kTitle      ? "DejaVu Sans Bold 20"
                     : b.kind == Block::kHeading  ? "DejaVu Sans Bold 13"
                     : b.kind == Block::kEmbedded ? "DejaVu Sans 7.5"
                                                  : "DejaVu Serif 11";
  PangoFontDescription* desc = pango_font_description_from_string(font);
  pango_layout_set_font_description(layout, desc);
  pango_font_description_free(desc);
  pango_layout_set_width(layout, static_cast<int>(width * PANGO_SCALE));
  pango_layout_set_wrap(layout, PANGO_WRAP_WORD_CHAR);
  if (b.kind == Block::kField) {
    char* label = g_markup_escape_text(Showable(b.label).c_str(), -1);
    char* text = g_markup_escape_text(Showable(b.text).c_str(), -1);
    const std::string markup = std::string("<b>") + label + ":</b>\t" + text;
    g_free(label);
    g_free(text);
    pango_layout_set_markup(layout, markup.c_str(), -1);
    PangoTabArray* tabs = pango_tab_array_new_with_positions(1, TRUE, PANGO_TAB_LEFT, 72);
    pango_layout_set_tabs(layout, tabs);
    pango_tab_array_free(tabs);
  } else {
    if (b.kind == Block::kParagraph) pango_layout_set_justify(layout, TRUE);
    const std::string text = Showable(b.text);
    pango_layout_set_text(layout, text.c_str(), static_cast<int>(text.size()));
  }
  return layout;
}

double LayoutHeight(PangoLayout* layout) {
  int w = 0, h = 0;
  pango_layout_get_size(layout, &w, &h);
  return static_cast<double>(h) / PANGO_SCALE;
}

double SpaceBefore(Block::Kind k) { return k == Block::kHeading ? 10 : k == Block::kField ? 0 : 0; }

void DrawRegion(cairo_t* cr, const Placed& p, const RegionContent& content) {
  cairo_save(cr);
  cairo_rectangle(cr, p.x, p.y, p.w, p.h);
  cairo_set_source_rgb(cr, 0.95, 0.95, 0.96);
  cairo_fill_preserve(cr);
  cairo_clip(cr);
  const Picture& pic = content.picture;
  if (!pic.empty()) {
    cairo_surface_t* s = PictureSurface(pic);
    cairo_translate(cr, p.x, p.y);
    cairo_scale(cr, p.w / pic.width, p.h / pic.height);
    cairo_set_source_surface(cr, s, 0, 0);
    cairo_pattern_set_filter(cairo_get_source(cr), CAIRO_FILTER_GOOD);
    cairo_paint(cr);
    cairo_surface_destroy(s);
  }
  cairo_restore(cr);
  cairo_save(cr);
  cairo_rectangle(cr, p.x + 0.25, p.y + 0.25, p.w - 0.5, p.h - 0.5);
  cairo_set_source_rgb(cr, 0.55, 0.57, 0.62);
  cairo_set_line_width(cr, 0.5);
  cairo_stroke(cr);
  Block caption = p.block;
  caption.text = content.caption;
  PangoLayout* layout = MakeLayout(caption, p.w);
  pango_layout_set_alignment(layout, PANGO_ALIGN_CENTER);
  // The caption keeps to its two lines (a long error list ends in "…"; the
  // whole of it is on stderr) instead of running over the text below.
  pango_layout_set_ellipsize(layout, PANGO_ELLIPSIZE_END);
  pango_layout_set_height(layout, -2);
  cairo_move_to(cr, p.x, p.y + p.h + kCaptionGap);
  cairo_set_source_rgb(cr, 0.35, 0.36, 0.4);
  pango_cairo_show_layout(cr, layout);
  g_object_unref(layout);
  cairo_restore(cr);
}

}  // namespace

std::vector<Block> Blocks(const HostDocument& doc) {
  std::vector<Block> out;
  std::vector<size_t> path;
  Walk(doc, doc.document().nodes, path, false, out);
  return out;
}

// Paragraphs taller than a page, cut at line boundaries into pieces that
// each fit on one (a long paragraph used to be cut off at the page's foot).
static std::vector<Block> SplitTallParagraphs(const std::vector<Block>& blocks, double width,
                                              double page_height) {
  std::vector<Block> out;
  for (const Block& b : blocks) {
    if (b.kind != Block::kParagraph) {
      out.push_back(b);
      continue;
    }
    Block rest = b;
    rest.text = Showable(rest.text);  // the text the layout's byte indices refer to
    for (;;) {
      PangoLayout* layout = MakeLayout(rest, width);
      if (LayoutHeight(layout) <= page_height) {
        g_object_unref(layout);
        out.push_back(rest);
        break;
      }
      // The first line that does not end on this page starts the next piece.
      int cut = -1;
      PangoLayoutIter* it = pango_layout_get_iter(layout);
      do {
        PangoRectangle logical;
        pango_layout_iter_get_line_extents(it, nullptr, &logical);
        const double bottom = static_cast<double>(logical.y + logical.height) / PANGO_SCALE;
        if (bottom > page_height) {
          cut = pango_layout_iter_get_index(it);
          break;
        }
      } while (pango_layout_iter_next_line(it));
      pango_layout_iter_free(it);
      g_object_unref(layout);
      if (cut <= 0 || static_cast<size_t>(cut) >= rest.text.size()) {
        out.push_back(rest);  // a single line taller than a page: nothing to cut
        break;
      }
      Block piece = rest;
      piece.text = rest.text.substr(0, static_cast<size_t>(cut));
      while (!piece.text.empty() && piece.text.back() == ' ') piece.text.pop_back();
      out.push_back(piece);
      rest.text = rest.text.substr(static_cast<size_t>(cut));
    }
  }
  return out;
}

std::vector<Page> Paginate(const std::vector<Block>& all_blocks, const HostDocument& doc,
                           const PageStyle& style) {
  std::vector<Page> pages(1);
  const double text_width = style.width - 2 * style.margin;
  const std::vector<Block> blocks =
      SplitTallParagraphs(all_blocks, text_width, style.height - 2 * style.margin);
  double y = style.margin;
  Block::Kind previous = Block::kTitle;
  bool first = true;
  auto height_of = [&](const Block& b) {
    if (b.kind == Block::kEmbedded) {
      const Embedded& e = doc.items()[static_cast<size_t>(b.item)];
      return e.height * std::min(1.0, text_width / e.width) + kCaptionGap + kCaptionHeight;
    }
    PangoLayout* layout = MakeLayout(b, text_width);
    const double h = LayoutHeight(layout);
    g_object_unref(layout);
    return h;
  };
  for (size_t i = 0; i < blocks.size(); ++i) {
    const Block& b = blocks[i];
    Placed p;
    p.block = b;
    double height;
    if (b.kind == Block::kEmbedded) {
      const Embedded& e = doc.items()[static_cast<size_t>(b.item)];
      const double k = std::min(1.0, text_width / e.width);
      p.w = e.width * k;
      p.h = e.height * k;
      p.x = style.margin + (text_width - p.w) / 2;
      height = p.h + kCaptionGap + kCaptionHeight;
    } else {
      PangoLayout* layout = MakeLayout(b, text_width);
      p.x = style.margin;
      p.w = text_width;
      p.h = height = LayoutHeight(layout);
      g_object_unref(layout);
    }
    double gap = first                                                  ? 0
                 : previous == Block::kField && b.kind == Block::kField ? 2
                 : previous == Block::kField                            ? 2 * kGap
                                                                        : kGap;
    gap += first ? 0 : SpaceBefore(b.kind);
    // A heading stays with what follows it, and so does the paragraph that
    // introduces an embedded region.
    auto keeps_with_next = [&](size_t k) {
      return k + 1 < blocks.size() &&
             (blocks[k].kind == Block::kHeading ||
              (blocks[k].kind == Block::kParagraph && blocks[k + 1].kind == Block::kEmbedded));
    };
    double keep = 0;
    for (size_t k = i; keeps_with_next(k); ++k) keep += kGap + height_of(blocks[k + 1]);
    if (!first && y + gap + height + keep > style.height - style.margin) {
      pages.emplace_back();
      y = style.margin;
      gap = 0;
    }
    p.y = y + gap;
    y = p.y + height;
    pages.back().items.push_back(p);
    previous = b.kind;
    first = false;
  }
  return pages;
}

void DrawPage(cairo_t* cr, const Page& page, const std::vector<RegionContent>& regions,
              const PageStyle& style) {
  cairo_save(cr);
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);  // the whole surface: a scaled page may not cover the last pixel
  const Placed* last_field = nullptr;
  for (const Placed& p : page.items) {
    // A rule under the fields that open a memo.
    if (last_field && p.block.kind != Block::kField) {
      const double ry = (last_field->y + last_field->h + p.y) / 2;
      cairo_move_to(cr, style.margin, ry);
      cairo_line_to(cr, style.width - style.margin, ry);
      cairo_set_source_rgb(cr, 0.6, 0.6, 0.6);
      cairo_set_line_width(cr, 0.6);
      cairo_stroke(cr);
    }
    last_field = p.block.kind == Block::kField ? &p : nullptr;
    if (p.block.kind == Block::kEmbedded) {
      const size_t i = static_cast<size_t>(p.block.item);
      DrawRegion(cr, p, i < regions.size() ? regions[i] : RegionContent{});
      continue;
    }
    PangoLayout* layout = MakeLayout(p.block, p.w);
    cairo_move_to(cr, p.x, p.y);
    cairo_set_source_rgb(cr, 0.1, 0.1, 0.12);
    pango_cairo_show_layout(cr, layout);
    g_object_unref(layout);
  }
  cairo_restore(cr);
}

namespace {
cairo_status_t Append(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}
}  // namespace

bool WritePdf(const std::string& path, const std::vector<Page>& pages,
              const std::vector<RegionContent>& regions, std::string* error,
              const PageStyle& style) {
  std::string bytes;
  cairo_surface_t* s =
      cairo_pdf_surface_create_for_stream(Append, &bytes, style.width, style.height);
  cairo_t* cr = cairo_create(s);
  for (const Page& page : pages) {
    DrawPage(cr, page, regions, style);
    cairo_show_page(cr);
  }
  cairo_destroy(cr);
  cairo_surface_finish(s);
  const cairo_status_t status = cairo_surface_status(s);
  cairo_surface_destroy(s);
  if (status != CAIRO_STATUS_SUCCESS) {
    if (error) *error = std::string("PDF: ") + cairo_status_to_string(status);
    return false;
  }
  return document::WriteFileAtomic(path, bytes, error);
}

std::string PagePng(const Page& page, const std::vector<RegionContent>& regions, double dpi,
                    std::string* error, const PageStyle& style) {
  const double k = dpi / 72.0;
  const int w = static_cast<int>(std::lround(style.width * k));
  const int h = static_cast<int>(std::lround(style.height * k));
  cairo_surface_t* s = cairo_image_surface_create(CAIRO_FORMAT_RGB24, w, h);
  cairo_t* cr = cairo_create(s);
  cairo_scale(cr, k, k);
  DrawPage(cr, page, regions, style);
  cairo_destroy(cr);
  std::string bytes;
  const cairo_status_t st = cairo_surface_write_to_png_stream(s, Append, &bytes);
  cairo_surface_destroy(s);
  if (st == CAIRO_STATUS_SUCCESS) return bytes;
  if (error) *error = std::string("PNG: ") + cairo_status_to_string(st);
  return {};
}

bool WritePngPages(const std::string& path, const std::vector<Page>& pages,
                   const std::vector<RegionContent>& regions, double dpi,
                   std::vector<std::string>* written, std::string* error, const PageStyle& style) {
  for (size_t i = 0; i < pages.size(); ++i) {
    std::string out = path;
    if (i > 0) {
      const size_t dot = path.rfind('.');
      out = path.substr(0, dot) + "-" + std::to_string(i + 1) + path.substr(dot);
    }
    const std::string bytes = PagePng(pages[i], regions, dpi, error, style);
    if (bytes.empty()) return false;
    if (!document::WriteFileAtomic(out, bytes, error)) return false;
    if (written) written->push_back(out);
  }
  return true;
}

std::vector<TextLine> PageLines(const Page& page) {
  std::vector<TextLine> out;
  for (const Placed& p : page.items) {
    if (p.block.kind == Block::kEmbedded) continue;
    PangoLayout* layout = MakeLayout(p.block, p.w);
    const std::string text = pango_layout_get_text(layout);
    const PangoFontDescription* desc = pango_layout_get_font_description(layout);
    TextLine font;
    if (desc) {
      font.size = static_cast<double>(pango_font_description_get_size(desc)) / PANGO_SCALE;
      const char* family = pango_font_description_get_family(desc);
      font.family = family ? family : "";
      font.bold = pango_font_description_get_weight(desc) >= PANGO_WEIGHT_BOLD;
    }
    PangoLayoutIter* it = pango_layout_get_iter(layout);
    bool first_line = true;
    do {
      PangoLayoutLine* line = pango_layout_iter_get_line_readonly(it);
      const size_t start = static_cast<size_t>(line->start_index);
      const size_t end = std::min(text.size(), start + static_cast<size_t>(line->length));
      PangoRectangle logical;
      pango_layout_iter_get_line_extents(it, nullptr, &logical);
      auto x_of = [&](size_t index) {  // points from the layout's left
        int x = 0;
        pango_layout_line_index_to_x(line, static_cast<int>(index), FALSE, &x);
        return static_cast<double>(logical.x + x) / PANGO_SCALE;
      };
      // A tab (a field's label and its text) splits the line: each piece
      // is a line of its own, where the tab stop put it.
      for (size_t a = start; a < end;) {
        const size_t tab = std::min(end, text.find('\t', a));
        std::string piece = text.substr(a, tab - a);
        size_t kept = piece.size();
        while (kept > 0 && std::isspace(static_cast<unsigned char>(piece[kept - 1]))) --kept;
        piece.resize(kept);
        if (!piece.empty()) {
          TextLine l = font;
          l.bold = font.bold || (p.block.kind == Block::kField && first_line && a == start &&
                                 tab < end);  // the label
          l.x = p.x + x_of(a);
          const double right =
              tab < end ? x_of(tab) : static_cast<double>(logical.x + logical.width) / PANGO_SCALE;
          l.w = std::max(0.0, p.x + right - l.x);
          l.y = p.y + static_cast<double>(logical.y) / PANGO_SCALE;
          l.h = static_cast<double>(logical.height) / PANGO_SCALE;
          l.baseline = p.y + static_cast<double>(pango_layout_iter_get_baseline(it)) / PANGO_SCALE;
          l.text = std::move(piece);
          out.push_back(std::move(l));
        }
        a = tab + 1;
      }
      first_line = false;
    } while (pango_layout_iter_next_line(it));
    pango_layout_iter_free(it);
    g_object_unref(layout);
  }
  return out;
}

std::string LayoutJson(const std::vector<Page>& pages, const PageStyle& style) {
  std::ostringstream s;
  s << "{\"page\":{\"width\":" << style.width << ",\"height\":" << style.height << "},\"pages\":[";
  for (size_t i = 0; i < pages.size(); ++i) {
    s << (i ? "," : "") << "[";
    for (size_t j = 0; j < pages[i].items.size(); ++j) {
      const Placed& p = pages[i].items[j];
      static const char* kinds[] = {"title", "heading", "field", "paragraph", "embedded"};
      s << (j ? "," : "") << "{\"kind\":\"" << kinds[p.block.kind] << "\",\"x\":" << p.x
        << ",\"y\":" << p.y << ",\"w\":" << p.w << ",\"h\":" << p.h;
      if (p.block.kind == Block::kEmbedded) s << ",\"item\":" << p.block.item + 1;
      s << "}";
    }
    s << "]";
  }
  s << "]}";
  return s.str();
}

}  // namespace asgard::host
