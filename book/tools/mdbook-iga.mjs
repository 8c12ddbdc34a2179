#!/usr/bin/env node
// The book's mdBook preprocessor (book.toml: [preprocessor.iga]).
//
// 1. Maths. $…$ and $$…$$ are rendered to HTML by KaTeX at build time, so the
//    built book needs neither JavaScript nor a network to show them; the
//    stylesheet and fonts are the committed copies in src/katex/, whose
//    version must equal the katex package pinned in package-lock.json.
//    An invalid formula fails the build (option `throw-on-error`, default true).
// 2. API links. [text](api:path::to::item) becomes a link to the item's rustdoc
//    page in the book's output (`api-url`), and so does inline code holding a
//    full path, `iga_contact::solver::bfgs::solve`. [`solve`](api:) takes the
//    path from the link text. A path that rustdoc does not know fails the build.
//    Other inline code that names exactly one item (`Problem::kernel`,
//    `solve()`) links to it too. IGA_BOOK_REPORT_UNLINKED=1 lists inline code
//    left unlinked because its name is ambiguous.
//
// Fenced code, inline code and HTML comments are never changed (other than
// wrapping a full-path code span in a link).

import fs from "node:fs";
import path from "node:path";
import { createRequire } from "node:module";
import { lineOf, stripAnchors, transform } from "./scan.mjs";
import { ApiIndex } from "./api.mjs";

const require = createRequire(import.meta.url);

if (process.argv[2] === "supports") {
  // Maths is pre-rendered HTML and links are HTML pages: only the html renderer.
  process.exit(process.argv[3] === "html" ? 0 : 1);
}

let katex;
try {
  katex = require("katex");
} catch {
  console.error(
    "error: the npm package katex is missing: run `npm ci --prefix book/tools` " +
      "(scripts/install-tools.sh does this)",
  );
  process.exit(1);
}

/// Text between tags is escaped so that Markdown, which parses the chapter after
/// this preprocessor, cannot read KaTeX's output as emphasis, links, table cell
/// separators or escapes (e.g. the TeX source in the MathML annotation).
/// Newlines (in the annotation, and in the path data of \sqrt's SVG) become
/// spaces: a newline would end a table row, and a line starting with "- " in a
/// multi-line formula would start a list.
function protect(html) {
  return html
    .replace(/>([^<]+)</g, (_, text) =>
      `>${text.replace(/[\\`*_[\]~$|!'"-]/g, (c) => `&#${c.charCodeAt(0)};`)}<`,
    )
    .replace(/[ \t]*\r?\n[ \t]*/g, " ");
}

/// The path in a link text: `Problem::kernel(Kernel::Tied)` → `Problem::kernel()`.
function rustPathOf(text) {
  return text.replace(/`/g, "").trim().replace(/\(.*\)$/, "()");
}

const FULL_PATH = /^\s*(iga_contact(?:::[A-Za-z_]\w*)+)(\(\))?\s*$/;
// Inline code that may name an item: `solve`, `Problem::kernel`, `kernel(...)`.
const NAME_LIKE = /^[A-Za-z_]\w*(::[A-Za-z_]\w*)*(\(.*\))?$/;

function main() {
  const [ctx, book] = JSON.parse(fs.readFileSync(0, "utf8"));
  const cfg = ctx.config?.preprocessor?.iga ?? {};
  const throwOnError = cfg["throw-on-error"] ?? true;
  const macros = cfg.macros ?? {};
  const crate = cfg["api-crate"] ?? "iga_contact";
  const apiUrl = (cfg["api-url"] ?? "api").replace(/\/$/, "");
  const docDir = path.resolve(
    ctx.root,
    process.env.IGA_BOOK_API_DOC_DIR ?? cfg["api-doc-dir"] ?? "../target/doc",
  );

  let api = null;
  const apiIndex = () => (api ??= new ApiIndex(docDir, crate));

  const errors = [];
  // IGA_BOOK_REPORT_UNLINKED=1 lists inline code whose name fits several API
  // items and so stays unlinked (a report, not an error).
  const reportUnlinked = process.env.IGA_BOOK_REPORT_UNLINKED === "1";
  const unlinked = [];
  let links = 0;
  let formulas = 0;

  const visit = (item) => {
    if (Array.isArray(item)) return item.forEach(visit);
    if (item === null || typeof item !== "object") return;
    if (item.Chapter) {
      processChapter(item.Chapter);
      visit(item.Chapter.sub_items);
      return;
    }
    Object.values(item).forEach(visit);
  };

  function processChapter(ch) {
    const where = ch.source_path ?? ch.path ?? ch.name;
    const depth = ch.path ? ch.path.split("/").length - 1 : 0;
    const root = "../".repeat(depth);
    const src = stripAnchors(ch.content);
    const fail = (offset, msg) => errors.push(`${where}:${lineOf(src, offset)}: ${msg}`);

    const link = (text, target, offset) => {
      try {
        const file = apiIndex().resolve(target);
        links++;
        return `[${text}](${root}${apiUrl}/${crate}/${file})`;
      } catch (e) {
        fail(offset, `api link: ${e.message}`);
        return text;
      }
    };

    try {
      ch.content = transform(src, {
        math(tex, display, offset) {
          formulas++;
          try {
            return protect(
              katex.renderToString(tex, {
                displayMode: display,
                throwOnError,
                macros,
                // Anything KaTeX would only warn about is an error too.
                strict: "error",
                trust: false,
                output: "htmlAndMathml",
              }),
            );
          } catch (e) {
            fail(offset, `KaTeX: ${e.message}`);
            return "";
          }
        },
        apiLink(text, target, offset) {
          return link(text, target === "" ? rustPathOf(text) : target, offset);
        },
        codeSpan(raw, inner, offset, before) {
          if (before === "[") return raw; // the text of a link already
          const m = FULL_PATH.exec(inner);
          if (m) return link(raw, m[1], offset);
          if (!NAME_LIKE.test(inner)) return raw;
          // Inline code that names exactly one item links to its page, so a
          // name in the prose is always one click from its documentation
          // without the author writing the link.
          let file;
          try {
            file = apiIndex().resolve(rustPathOf(inner));
          } catch (e) {
            if (reportUnlinked && /names several items/.test(e.message)) {
              unlinked.push(`${where}:${lineOf(src, offset)}: ${raw} (${e.message})`);
            }
            return raw; // not an item (a scene key, a variable), or ambiguous
          }
          links++;
          return `[${raw}](${root}${apiUrl}/${crate}/${file})`;
        },
      });
    } catch (e) {
      fail(e.offset ?? 0, e.message);
    }
  }

  visit(book);
  if (errors.length > 0) {
    for (const e of errors) console.error(`error: ${e}`);
    console.error(`error: the book preprocessor found ${errors.length} problem(s)`);
    process.exit(1);
  }
  if (reportUnlinked) {
    for (const u of unlinked) console.error(`[iga] unlinked: ${u}`);
  }
  const report = reportUnlinked ? `, ${unlinked.length} code names left unlinked as ambiguous` : "";
  console.error(`[iga] ${formulas} formulas rendered, ${links} API links resolved${report}`);
  process.stdout.write(JSON.stringify(book));
}

main();
