// Download links for generated tables: after each `{{#include generated/<ch>/<name>.md}}`
// whose `<name>.csv` exists beside it, a small "Download: <name>.csv" line, so that
// every table of results links the data it was written from.
//
// It runs before mdBook's links preprocessor (book.toml, [preprocessor.iga-downloads]),
// while the include directives are still visible; fenced code and escaped includes
// (\{{#include …}}) are left alone.

const FENCE = /^\s*(```|~~~)/;
const INCLUDE = /^\s*\{\{#include\s+(generated\/[^\s:}]+)\.md\s*\}\}\s*$/;

/// `content` with a download line after each whole-file include of a generated
/// Markdown table whose CSV exists; `exists(path)` answers for a path relative to
/// the chapter's folder.
export function downloadLinks(content, exists) {
  const out = [];
  let fence = null;
  for (const line of content.split("\n")) {
    out.push(line);
    const f = FENCE.exec(line);
    if (f) {
      if (fence === null) fence = f[1];
      else if (f[1] === fence) fence = null;
      continue;
    }
    if (fence !== null) continue;
    const m = INCLUDE.exec(line);
    if (!m) continue;
    const csv = `${m[1]}.csv`;
    if (!exists(csv)) continue;
    const name = csv.slice(csv.lastIndexOf("/") + 1);
    out.push("", `<p class="download"><small>Download: <a href="${csv}">${name}</a></small></p>`, "");
  }
  return out.join("\n");
}
