// Tests of the download links: `node --test book/tools/`.
import test from "node:test";
import assert from "node:assert/strict";
import fs from "node:fs";
import os from "node:os";
import path from "node:path";
import { spawnSync } from "node:child_process";
import { fileURLToPath } from "node:url";
import { downloadLinks } from "./downloads.mjs";

const here = path.dirname(fileURLToPath(import.meta.url));
const has = (...files) => (rel) => files.includes(rel);

test("a generated table with a CSV gets a download line after it", () => {
  const src = "**Table H1.** x\n\n{{#include generated/hertz/ladder.md}}\n\nText.\n";
  const out = downloadLinks(src, has("generated/hertz/ladder.csv"));
  assert.match(out, /\{\{#include generated\/hertz\/ladder\.md\}\}\n\n<p class="download">/);
  assert.match(out, /<a href="generated\/hertz\/ladder\.csv">ladder\.csv<\/a>/);
  assert.ok(out.endsWith("\n\nText.\n"));
});

test("no CSV, an anchor, an escaped include or fenced code: no link", () => {
  const none = has();
  const table = "{{#include generated/a/t.md}}\n";
  assert.equal(downloadLinks(table, none), table);
  const csv = has("generated/a/t.csv");
  for (const src of [
    "{{#include generated/a/facts.txt:key}}\n",
    "\\{{#include generated/a/t.md}}\n",
    "```text\n{{#include generated/a/t.md}}\n```\n",
    "see {{#include generated/a/t.md}} inline\n",
  ]) {
    assert.equal(downloadLinks(src, csv), src, src);
  }
});

test("the preprocessor links tables of the chapter's folder and passes the book through", () => {
  const root = fs.mkdtempSync(path.join(os.tmpdir(), "downloads-"));
  fs.mkdirSync(path.join(root, "src/generated/c"), { recursive: true });
  fs.writeFileSync(path.join(root, "src/generated/c/t.csv"), "a,b\n1,2\n");
  const chapter = (content) => ({
    Chapter: { name: "C", content, source_path: "c.md", path: "c.md", sub_items: [] },
  });
  const book = { items: [chapter("{{#include generated/c/t.md}}\n{{#include generated/c/u.md}}\n")] };
  const ctx = { root, config: { book: { src: "src" } } };
  const run = spawnSync(process.execPath, [path.join(here, "mdbook-downloads.mjs")], {
    input: JSON.stringify([ctx, book]),
    encoding: "utf8",
  });
  assert.equal(run.status, 0, run.stderr);
  const out = JSON.parse(run.stdout).items[0].Chapter.content;
  assert.equal((out.match(/class="download"/g) || []).length, 1);
  assert.match(out, /t\.csv/);
  assert.doesNotMatch(out, /u\.csv/);
});
