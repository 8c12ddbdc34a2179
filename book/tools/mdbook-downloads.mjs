#!/usr/bin/env node
// mdBook preprocessor (book.toml: [preprocessor.iga-downloads]): links each generated
// table to its CSV file for download; see downloads.mjs.

import fs from "node:fs";
import path from "node:path";
import { downloadLinks } from "./downloads.mjs";

if (process.argv[2] === "supports") {
  process.exit(process.argv[3] === "html" ? 0 : 1);
}

const [ctx, book] = JSON.parse(fs.readFileSync(0, "utf8"));
const src = path.resolve(ctx.root, ctx.config?.book?.src ?? "src");
let links = 0;

const visit = (item) => {
  if (Array.isArray(item)) return item.forEach(visit);
  if (item === null || typeof item !== "object") return;
  if (item.Chapter) {
    const ch = item.Chapter;
    if (typeof ch.content === "string" && ch.source_path) {
      const dir = path.join(src, path.dirname(ch.source_path));
      ch.content = downloadLinks(ch.content, (rel) => {
        const ok = fs.existsSync(path.join(dir, rel));
        if (ok) links++;
        return ok;
      });
    }
    visit(ch.sub_items);
    return;
  }
  Object.values(item).forEach(visit);
};

visit(book);
console.error(`[iga-downloads] ${links} tables linked to their CSV files`);
process.stdout.write(JSON.stringify(book));
