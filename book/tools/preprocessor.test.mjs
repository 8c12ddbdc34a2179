// Tests of the book preprocessor: `node --test book/tools/` (run by .ci/run).
import test from "node:test";
import assert from "node:assert/strict";
import fs from "node:fs";
import os from "node:os";
import path from "node:path";
import { spawnSync } from "node:child_process";
import { fileURLToPath } from "node:url";
import { stripAnchors, transform } from "./scan.mjs";
import { ApiIndex } from "./api.mjs";

const here = path.dirname(fileURLToPath(import.meta.url));

// Marks what the scanner hands to each handler, so the tests see exactly
// which parts of the source were treated as maths, links or code.
const mark = (src) =>
  transform(src, {
    math: (tex, display) => (display ? `<D:${tex}>` : `<I:${tex}>`),
    apiLink: (text, target) => `<L:${text}|${target}>`,
    codeSpan: (raw, inner, _o, before) => (inner.startsWith("iga_contact::") && before !== "[" ? `<C:${inner}>` : raw),
  });

test("inline and display maths are found", () => {
  assert.equal(mark("a $x^2$ b"), "a <I:x^2> b");
  assert.equal(mark("$$\nx\n\\tag{3}\n$$\n"), "<D:\nx\n\\tag{3}\n>\n");
  assert.equal(mark("if $k > $ `n`"), "if <I:k > > `n`");
});

test("code, escapes and prices are left alone", () => {
  const fenced = "```rust\nlet s = \"$x$\";\n```\n";
  assert.equal(mark(fenced), fenced);
  assert.equal(mark("~~~\n$$ not maths $$\n~~~\n"), "~~~\n$$ not maths $$\n~~~\n");
  assert.equal(mark("  ```text\n  $a$\n  ```\n$b$"), "  ```text\n  $a$\n  ```\n<I:b>");
  assert.equal(mark("`$x$` and ``a ` $y$``"), "`$x$` and ``a ` $y$``");
  assert.equal(mark("costs \\$5, not $x\\$y$"), "costs \\$5, not <I:x\\$y>");
  assert.equal(mark("from $5 to $6"), "from $5 to $6");
  assert.equal(mark("<!-- $x$ -->"), "<!-- $x$ -->");
  assert.equal(mark("$a\n\nb$"), "$a\n\nb$", "inline maths does not cross paragraphs");
});

test("unclosed display maths is an error with its offset", () => {
  assert.throws(() => mark("text\n$$\nx\n"), (e) => e.offset === 5);
});

test("api links and full-path code spans are found", () => {
  assert.equal(mark("see [`solve`](api:solver::bfgs::solve)."), "see <L:`solve`|solver::bfgs::solve>.");
  assert.equal(mark("[`solver::solve`](api:)"), "<L:`solver::solve`|>");
  assert.equal(mark("`iga_contact::geometry` and `x`"), "<C:iga_contact::geometry> and `x`");
  assert.equal(mark("[`iga_contact::a`](other.md)"), "[`iga_contact::a`](other.md)");
  assert.equal(mark("```\n[a](api:b)\n```\n"), "```\n[a](api:b)\n```\n");
});

function fakeDocs() {
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), "api-test-"));
  const crate = path.join(dir, "demo");
  fs.mkdirSync(path.join(crate, "solver"), { recursive: true });
  const a = (kind, href, full, name) => `<a class="${kind}" href="${href}" title="${kind} ${full}">${name}</a>`;
  fs.mkdirSync(path.join(crate, "other"), { recursive: true });
  fs.writeFileSync(
    path.join(crate, "index.html"),
    a("mod", "solver/index.html", "demo::solver", "solver") +
      a("mod", "other/index.html", "demo::other", "other") +
      `<code>pub use solver::${a("fn", "solver/fn.solve.html", "demo::solver::solve", "solve")};</code>`,
  );
  fs.writeFileSync(
    path.join(crate, "other", "index.html"),
    a("struct", "struct.Options.html", "demo::other::Options", "Options") +
      a("struct", "struct.Mesh.html", "demo::other::Mesh", "Mesh"),
  );
  fs.writeFileSync(path.join(crate, "other", "struct.Options.html"), '<h4 id="method.old"></h4>');
  fs.writeFileSync(path.join(crate, "other", "struct.Mesh.html"), '<h4 id="method.refine"></h4>');
  fs.writeFileSync(
    path.join(crate, "solver", "index.html"),
    a("fn", "fn.solve.html", "demo::solver::solve", "solve") +
      a("struct", "struct.Options.html", "demo::solver::Options", "Options") +
      a("macro", "macro.solve.html", "demo::solver::solve", "solve"),
  );
  fs.writeFileSync(path.join(crate, "solver", "struct.Options.html"), '<h4 id="method.new"></h4><span id="structfield.tol"></span>');
  return dir;
}

test("api paths resolve to rustdoc pages, members to anchors", () => {
  const api = new ApiIndex(fakeDocs(), "demo");
  assert.equal(api.resolve("solver::Options"), "solver/struct.Options.html");
  assert.equal(api.resolve("demo::solver::Options::new()"), "solver/struct.Options.html#method.new");
  assert.equal(api.resolve("solver::Options::tol"), "solver/struct.Options.html#structfield.tol");
  assert.equal(api.resolve("solve"), "solver/fn.solve.html", "a re-export at the crate root");
  assert.equal(api.resolve("fn@solver::solve"), "solver/fn.solve.html");
  assert.equal(api.resolve("solver::solve!"), "solver/macro.solve.html");
  // Leading modules may be left out when the rest is unique.
  assert.equal(api.resolve("Mesh::refine"), "other/struct.Mesh.html#method.refine");
  assert.equal(api.resolve("Options::new"), "solver/struct.Options.html#method.new");
  assert.equal(api.resolve("Options::old"), "other/struct.Options.html#method.old");
  assert.equal(api.resolve("solver::solve()"), "solver/fn.solve.html");
});

test("unknown and ambiguous api paths are errors naming the candidates", () => {
  const api = new ApiIndex(fakeDocs(), "demo");
  assert.throws(() => api.resolve("solver::solve"), /ambiguous: write one of fn@solver::solve, macro@solver::solve/);
  assert.throws(() => api.resolve("solver::Option"), /not an item of the crate demo/);
  assert.throws(() => api.resolve("Options"), /names several items \(solver\/Options, other\/Options\)/);
  assert.throws(() => api.resolve("Options::tidy"), /`Options::tidy` is not an item of the crate demo/);
  assert.throws(() => api.resolve("tidy"), /is not an item/);
  assert.throws(() => api.resolve("solver::Options::old"), /has no method, field, variant or associated item `old`/);
});

function runPreprocessor(content, docDir) {
  const ctx = { root: here, config: { preprocessor: { iga: { "api-doc-dir": docDir, "api-crate": "demo" } } } };
  const book = { items: [{ Chapter: { name: "c", content, path: "part/c.md", source_path: "part/c.md", sub_items: [] } }] };
  return spawnSync(process.execPath, [path.join(here, "mdbook-iga.mjs")], {
    input: JSON.stringify([ctx, book]),
    encoding: "utf8",
  });
}

test("the preprocessor renders maths Markdown-safely and links relative to the chapter", () => {
  const r = runPreprocessor(
    "A [`Options`](api:solver::Options), [`Mesh::refine(2)`](api:).\n\n$a_*b|c$\n\n$$\nx\n- y \\tag{7}\n$$\n",
    fakeDocs(),
  );
  assert.equal(r.status, 0, r.stderr);
  const [link, inline, display] = JSON.parse(r.stdout).items[0].Chapter.content.split("\n\n");
  assert.equal(
    link,
    "A [`Options`](../api/demo/solver/struct.Options.html), " +
      "[`Mesh::refine(2)`](../api/demo/other/struct.Mesh.html#method.refine).",
  );
  assert.match(display, /^<span class="katex-display">.*class="tag"/);
  // KaTeX's HTML holds no newline, and no Markdown punctuation between its tags.
  for (const html of [inline, display]) {
    assert.doesNotMatch(html.trimEnd(), /\n/);
    for (const text of html.match(/>[^<]+</g)) assert.doesNotMatch(text, /[*_|\\`-]/, text);
  }
  assert.match(inline, /&#42;/, "the * of the TeX source is kept, as an entity");
});

test("the preprocessor fails on bad maths and unknown api names, naming file and line", () => {
  const r = runPreprocessor("line one\n$\\frac{1}$ and [x](api:nope)\n", fakeDocs());
  assert.equal(r.status, 1);
  assert.match(r.stderr, /part\/c\.md:2: KaTeX: /);
  assert.match(r.stderr, /part\/c\.md:2: api link: `nope` is not an item/);
});

test("inline code naming exactly one item links to it; other code stays code", () => {
  const r = runPreprocessor("`Mesh::refine(2)`, `solve()`, `Options`, `tol = 1`, `nope`, [`Mesh`](api:).\n", fakeDocs());
  assert.equal(r.status, 0, r.stderr);
  assert.equal(
    JSON.parse(r.stdout).items[0].Chapter.content,
    "[`Mesh::refine(2)`](../api/demo/other/struct.Mesh.html#method.refine), " +
      "[`solve()`](../api/demo/solver/fn.solve.html), `Options`, `tol = 1`, `nope`, " +
      "[`Mesh`](../api/demo/other/struct.Mesh.html).\n",
  );
});

test("anchor lines of whole-file includes are removed, nothing else", () => {
  const src = "```rust\n// ANCHOR: all\nfn main() {}\n    // ANCHOR_END: all\n# ANCHOR: top\nlet x = 1; // ANCHOR in a comment stays\n```\n";
  assert.equal(stripAnchors(src), "```rust\nfn main() {}\nlet x = 1; // ANCHOR in a comment stays\n```\n");
});
