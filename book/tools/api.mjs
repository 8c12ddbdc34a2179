// Resolves item paths such as `solver::bfgs::solve` or `problem::Problem::kernel`
// to the page rustdoc wrote for them, by reading rustdoc's own HTML output.
//
// rustdoc's machine-readable JSON output is nightly-only and its search index
// changes format between releases, but every module page lists its items (and
// its re-exports) as <a class="KIND" href="…" title="KIND full::path">: that is
// what this reads. Members (methods, fields, variants, associated items) are
// anchors on their parent's page, checked by their id.

import fs from "node:fs";
import path from "node:path";

const ITEM = /<a class="(\w+)" href="([^"#]+)" title="(\w+) ([\w:]+)">/g;
const MEMBER_PREFIXES = [
  "method",
  "tymethod",
  "variant",
  "structfield",
  "associatedconstant",
  "associatedtype",
];
const PARENT_KINDS = new Set(["struct", "enum", "trait", "union", "type"]);

export class ApiIndex {
  #scanned;

  /// `docDir`: rustdoc's output folder (target/doc); `crate`: the crate name.
  constructor(docDir, crate) {
    this.docDir = docDir;
    this.crate = crate;
    this.root = path.join(docDir, crate);
    if (!fs.existsSync(path.join(this.root, "index.html"))) {
      throw new Error(
        `rustdoc output not found at ${this.root}/index.html: ` +
          "run `cargo doc --no-deps --release` before building the book " +
          "(scripts/build-book.sh does both)",
      );
    }
    // "module::path::Name" (without the crate) → [{kind, file}], file relative to docDir/crate.
    this.items = new Map();
    this.pages = new Map();
    this.#scanned = new Set();
    this.#scanModule("", this.root);
  }

  #add(key, kind, file) {
    const list = this.items.get(key) ?? [];
    if (!list.some((e) => e.file === file)) list.push({ kind, file });
    this.items.set(key, list);
  }

  #scanModule(modPath, dir) {
    const html = fs.readFileSync(path.join(dir, "index.html"), "utf8");
    const relDir = path.relative(this.root, dir).split(path.sep).join("/");
    for (const m of html.matchAll(ITEM)) {
      const [, kind, href, titleKind, full] = m;
      if (kind !== titleKind || /^[a-z]+:/.test(href)) continue;
      const name = full.split("::").pop();
      const key = modPath ? `${modPath}::${name}` : name;
      const file = path.posix.normalize(path.posix.join(relDir, href));
      if (file.startsWith("..")) continue; // another crate's page
      this.#add(key, kind, file);
      if (kind === "mod" && !this.#scanned.has(file)) {
        this.#scanned.add(file);
        this.#scanModule(key, path.join(this.root, path.posix.dirname(file)));
      }
    }
  }

  #ids(file) {
    if (!this.pages.has(file)) {
      const html = fs.readFileSync(path.join(this.root, file), "utf8");
      this.pages.set(file, new Set([...html.matchAll(/\sid="([^"]+)"/g)].map((m) => m[1])));
    }
    return this.pages.get(file);
  }

  /// Suggestions for an unknown path: known items with the same last segment.
  #similar(name) {
    const out = [];
    for (const [key, entries] of this.items) {
      if (key.split("::").pop() === name) out.push(`${key} (${entries[0].kind})`);
    }
    return out;
  }

  /// The page of the item at exactly `segs` (a module path from the crate
  /// root, possibly ending in a member), or null if there is none.
  #exact(segs, want, target) {
    const key = segs.join("::");
    let found = this.items.get(key);
    if (found && want) found = found.filter((e) => e.kind === want);
    if (found && found.length === 1) return found[0].file;
    if (found && found.length > 1) {
      const kinds = found.map((e) => `${e.kind}@${key}`).join(", ");
      throw new Error(`\`${target}\` is ambiguous: write one of ${kinds}`);
    }
    if (segs.length >= 2) {
      const parentKey = segs.slice(0, -1).join("::");
      const parents = (this.items.get(parentKey) ?? []).filter((e) => PARENT_KINDS.has(e.kind));
      const member = segs[segs.length - 1];
      for (const p of parents) {
        const ids = this.#ids(p.file);
        for (const prefix of MEMBER_PREFIXES) {
          if (want === "fn" ? !prefix.endsWith("method") : want && prefix !== want) continue;
          if (ids.has(`${prefix}.${member}`)) return `${p.file}#${prefix}.${member}`;
        }
      }
      if (parents.length > 0) {
        throw new Error(
          `\`${target}\`: ${parentKey} has no method, field, variant or associated item \`${member}\``,
        );
      }
    }
    return null;
  }

  /**
   * The page (and anchor) of `target`, relative to the crate's doc folder,
   * e.g. "solver/bfgs/fn.solve.html". `target` may start with the crate name
   * or leave out leading modules (`KnotVector::new`) if the rest is unique,
   * or `crate::`, may end in `()` (a function or method) or `!` (a macro),
   * and may carry a rustdoc-style disambiguator (`fn@`, `struct@`, `method@`, …). Throws with a clear message
   * when the item does not exist or is ambiguous.
   */
  resolve(target) {
    let t = target.trim();
    let want = null;
    const d = /^(\w+)@(.*)$/.exec(t);
    if (d) [, want, t] = d;
    // Like rustdoc's intra-doc links: `f()` is a function or method, `m!` a macro.
    if (t.endsWith("()")) [want, t] = [want ?? "fn", t.slice(0, -2)];
    else if (t.endsWith("!")) [want, t] = [want ?? "macro", t.slice(0, -1)];
    const segs = t.split("::").filter((s) => s.length > 0);
    if (segs[0] === this.crate || segs[0] === "crate") segs.shift();
    if (segs.length === 0) return "index.html";
    if (!segs.every((s) => /^[A-Za-z_]\w*$/.test(s))) {
      throw new Error(`\`${target}\` is not a Rust path`);
    }
    const exact = this.#exact(segs, want, target);
    if (exact !== null) return exact;
    // A path may leave out its leading modules when the rest names exactly
    // one item: `KnotVector::new` for `nurbs::knots::KnotVector::new`.
    const found = new Set();
    for (const [key, entries] of this.items) {
      if (key === segs[0] || !key.endsWith(`::${segs[0]}`)) continue;
      if (segs.length > 1 && !entries.some((e) => PARENT_KINDS.has(e.kind))) continue;
      try {
        const r = this.#exact([...key.split("::"), ...segs.slice(1)], want, target);
        if (r !== null) found.add(r);
      } catch {
        // no such member under this candidate
      }
    }
    if (found.size === 1) return [...found][0];
    if (found.size > 1) {
      const pages = [...found].map((f) => f.replace(/\.html/, "").replace(/\/(\w+)\./, "/")).join(", ");
      throw new Error(`\`${target}\` names several items (${pages}): write more of its path`);
    }
    const like = this.#similar(segs[segs.length - 1]);
    const hint = like.length > 0 ? `; items of that name: ${like.join(", ")}` : "";
    throw new Error(`\`${target}\` is not an item of the crate ${this.crate} in ${this.root}${hint}`);
  }
}
