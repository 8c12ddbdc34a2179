// A small scanner over the Markdown of one chapter. It finds the three things
// the book preprocessor rewrites — maths ($…$, $$…$$), api: links and inline
// code naming a library item — and leaves everything else byte for byte:
// fenced code blocks, inline code, HTML comments and backslash escapes.
//
// It is deliberately not a full CommonMark parser: the preprocessor must keep
// the source that mdBook parses afterwards unchanged wherever it does not act,
// and a scanner that only recognises these few constructs cannot reformat
// anything else.

const FENCE_OPEN = /^[ \t]*(`{3,}|~{3,})/;

/// A closing fence: same character, at least as long, nothing else on the line.
function closesFence(line, fence) {
  const m = /^[ \t]*(`{3,}|~{3,})[ \t]*$/.exec(line);
  return m !== null && m[1][0] === fence[0] && m[1].length >= fence.length;
}

/// Index of the closing `$` or `$$` (delimiter `delim`) from `from`, skipping
/// TeX escapes such as `\$`; -1 if none. Inline maths may not cross a blank
/// line (that would end the paragraph in Markdown).
function findClose(src, from, delim) {
  for (let j = from; j < src.length; j++) {
    const c = src[j];
    if (c === "\\") {
      j++;
      continue;
    }
    if (delim === "$" && c === "\n" && /^\n[ \t]*\n/.test(src.slice(j, j + 64))) {
      return -1;
    }
    if (src.startsWith(delim, j)) {
      if (delim === "$") {
        // No digit after the closing $, so that "costs $5 and $6" is not maths.
        // (A space before it is allowed, as mdbook-katex did: "$k > $".)
        if (/[0-9]/.test(src[j + 1] ?? "")) continue;
      }
      return j;
    }
  }
  return -1;
}

/// Length of the run of `ch` starting at `i`.
function runLength(src, i, ch) {
  let k = 0;
  while (src[i + k] === ch) k++;
  return k;
}

const API_LINK = /\[((?:[^\[\]\n\\`]|\\.|`[^`\n]*`)*)\]\(api:([^()\s]*)\)/y;

/**
 * Rewrite `src`, calling
 * - `math(tex, display, offset)` → HTML for each $…$ / $$…$$,
 * - `apiLink(text, target, offset)` → Markdown for each [text](api:target),
 * - `codeSpan(raw, inner, offset, before)` → Markdown for each inline code
 *   span outside such a link (`before` is the character before it).
 * Throws an Error with `offset` set for unclosed display maths.
 */
export function transform(src, { math, apiLink, codeSpan }) {
  let out = "";
  let i = 0;
  let lineStart = true;
  const n = src.length;
  while (i < n) {
    if (lineStart) {
      lineStart = false;
      const eol = src.indexOf("\n", i);
      const line = src.slice(i, eol === -1 ? n : eol);
      const open = FENCE_OPEN.exec(line);
      if (open && !(open[1][0] === "`" && line.slice(open[0].length).includes("`"))) {
        // Copy the whole fenced block, up to and including its closing fence.
        let j = eol === -1 ? n : eol + 1;
        while (j < n) {
          const e = src.indexOf("\n", j);
          const l = src.slice(j, e === -1 ? n : e);
          j = e === -1 ? n : e + 1;
          if (closesFence(l, open[1])) break;
        }
        out += src.slice(i, j);
        i = j;
        lineStart = true;
        continue;
      }
    }
    const c = src[i];
    if (c === "\n") {
      out += c;
      i++;
      lineStart = true;
    } else if (c === "\\") {
      out += src.slice(i, i + 2);
      i += 2;
    } else if (src.startsWith("<!--", i)) {
      const e = src.indexOf("-->", i + 4);
      const j = e === -1 ? n : e + 3;
      out += src.slice(i, j);
      i = j;
    } else if (c === "`") {
      const k = runLength(src, i, "`");
      let j = i + k;
      let close = -1;
      while ((j = src.indexOf("`".repeat(k), j)) !== -1) {
        if (runLength(src, j, "`") === k) {
          close = j;
          break;
        }
        j += runLength(src, j, "`");
      }
      if (close === -1) {
        out += src.slice(i, i + k);
        i += k;
      } else {
        const raw = src.slice(i, close + k);
        out += codeSpan(raw, src.slice(i + k, close), i, src[i - 1] ?? "");
        i = close + k;
      }
    } else if (c === "$" && src[i + 1] === "$") {
      const close = findClose(src, i + 2, "$$");
      if (close === -1) {
        const err = new Error("unclosed display maths `$$`");
        err.offset = i;
        throw err;
      }
      out += math(src.slice(i + 2, close), true, i);
      i = close + 2;
    } else if (c === "$" && src[i + 1] !== undefined && !/\s/.test(src[i + 1])) {
      const close = findClose(src, i + 1, "$");
      if (close === -1) {
        out += c;
        i++;
      } else {
        out += math(src.slice(i + 1, close), false, i);
        i = close + 1;
      }
    } else if (c === "[") {
      API_LINK.lastIndex = i;
      const m = API_LINK.exec(src);
      if (m) {
        out += apiLink(m[1], m[2], i);
        i += m[0].length;
      } else {
        out += c;
        i++;
      }
    } else {
      out += c;
      i++;
    }
  }
  return out;
}

/// 1-based line number of `offset` in `src`, for error messages.
export function lineOf(src, offset) {
  let line = 1;
  for (let j = 0; j < offset && j < src.length; j++) if (src[j] === "\n") line++;
  return line;
}

/// Removes mdBook's anchor lines (`// ANCHOR: name`, `# ANCHOR_END: name`)
/// from `src`. mdBook drops them from an include by anchor, but not from an
/// include of a whole file, so the chapters' "plain program" listings would
/// show them.
export function stripAnchors(src) {
  return src.replace(/^[ \t]*(?:\/\/|#)[ \t]*ANCHOR(?:_END)?:[ \t]*\w+[ \t]*\r?\n/gm, "");
}
