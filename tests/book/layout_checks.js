// What a reader of one loaded page cannot see: evaluated by tests/book/test_site.py
// in headless Chromium after MathJax has typeset the page. Returns plain data.
//
// "Cut off" means: part of the content lies outside the padding box of an
// ancestor that hides its overflow (overflow hidden/clip), or outside the
// scrollable area of an ancestor that scrolls (overflow auto/scroll), e.g. the
// left part of an equation pushed out by the theme's row-reverse flex box.
// Content that is wider than its column but sits in a box with a horizontal
// scroll bar is reachable, so it is not cut off.
() => {
  const TOL = 2;  // px: sub-pixel rounding, glyph overhang
  const main = document.querySelector("main") || document.body;

  const describe = (el) => {
    let s = el.tagName.toLowerCase();
    if (el.id) s += "#" + el.id;
    if (el.classList.length) s += "." + Array.from(el.classList).slice(0, 3).join(".");
    return s;
  };

  // the union of the boxes of an element and of its descendants, except those
  // inside a descendant that clips them itself (MathJax's stretchy delimiters
  // are built that way). MathJax's CHTML glyphs are CSS generated content, so
  // a Range over the text nodes would miss them.
  const boxesOf = (root) => {
    const out = [root];
    const walk = (el) => {
      for (const child of el.children) {
        out.push(child);
        if (getComputedStyle(child).overflow === "visible") walk(child);
      }
    };
    walk(root);
    return out;
  };
  const unionOf = (els) => {
    let r = null;
    for (const e of els) {
      const b = e.getBoundingClientRect();
      if (b.width === 0 && b.height === 0) continue;
      if (!r) r = { left: b.left, right: b.right, top: b.top, bottom: b.bottom };
      else {
        r.left = Math.min(r.left, b.left); r.right = Math.max(r.right, b.right);
        r.top = Math.min(r.top, b.top); r.bottom = Math.max(r.bottom, b.bottom);
      }
    }
    return r;
  };

  const textRect = (el) => {
    const range = document.createRange();
    range.selectNodeContents(el);
    const b = range.getBoundingClientRect();
    if (b.width === 0 && b.height === 0) return null;
    return { left: b.left, right: b.right, top: b.top, bottom: b.bottom };
  };

  // The first ancestor (from `el` itself upwards) that cuts part of `rect`
  // off, as a description; null when all of it can be seen. Horizontally a
  // box that scrolls shows everything within its scroll area; vertically
  // nothing may be hidden (an equation must not need a vertical scroll bar).
  const cutBy = (el, rect) => {
    let r = { ...rect };
    for (let a = el; a && a !== document.documentElement; a = a.parentElement) {
      const cs = getComputedStyle(a);
      const ox = cs.overflowX, oy = cs.overflowY;
      if (ox === "visible" && oy === "visible") continue;
      const b = a.getBoundingClientRect();
      const left = b.left + a.clientLeft, right = left + a.clientWidth;
      const top = b.top + a.clientTop, bottom = top + a.clientHeight;
      if (ox === "auto" || ox === "scroll") {
        const x0 = r.left - left + a.scrollLeft, x1 = r.right - left + a.scrollLeft;
        if (x0 < -TOL || x1 > a.scrollWidth + TOL)
          return `${describe(a)} (overflow ${ox}) cannot scroll to it: content ${Math.round(x0)}..${Math.round(x1)} px, scroll area 0..${a.scrollWidth} px`;
      } else if (ox !== "visible" && (r.left < left - TOL || r.right > right + TOL)) {
        return `${describe(a)} (overflow ${ox}) hides ${Math.round(Math.max(0, left - r.left))} px on the left and ${Math.round(Math.max(0, r.right - right))} px on the right`;
      }
      if (oy !== "visible" && a !== main && (r.top < top - TOL || r.bottom > bottom + TOL)
          && a.clientHeight < window.innerHeight) {
        return `${describe(a)} (overflow-y ${oy}) hides ${Math.round(Math.max(0, top - r.top))} px at the top and ${Math.round(Math.max(0, r.bottom - bottom))} px at the bottom`;
      }
      // what is visible of it from here on: in a box that scrolls sideways (and reaches
      // it, checked above) the reader scrolls it into the box's own width; in a box that
      // clips, only the part inside the box
      if (ox === "auto" || ox === "scroll") r = { ...r, left: left, right: right };
      else if (ox !== "visible") r = { ...r, left: Math.max(r.left, left), right: Math.min(r.right, right) };
      if (r.right <= r.left) return `${describe(a)} shows none of it`;
    }
    return null;
  };

  // the TeX source of each typeset formula, for the messages
  const source = new Map();
  try {
    for (const item of window.MathJax.startup.document.math) {
      if (item.typesetRoot) source.set(item.typesetRoot, item.math);
    }
  } catch (e) { /* no MathJax on this page */ }

  const label = (el) => {
    const tex = (source.get(el) || el.textContent).replace(/\s+/g, " ").trim();
    const tag = tex.match(/\\tag\{([^}]*)\}/);
    return (tag ? `(${tag[1]}) ` : "") + tex.replace(/^\\displaystyle\s*/, "").slice(0, 70);
  };

  // --- maths: every typeset formula, display or in-line
  const math = { displays: 0, inline: 0, cut: [], vertical: [] };
  for (const c of main.querySelectorAll("mjx-container")) {
    const display = c.getAttribute("display") === "true";
    if (display) math.displays++; else math.inline++;
    const m = c.querySelector(":scope > mjx-math");
    if (!m) continue;
    const rect = unionOf(boxesOf(m));
    if (!rect) continue;
    const why = cutBy(c, rect);
    if (why) math.cut.push(`${display ? "display" : "in-line"} ${label(c)}: ${why}`);
    // an equation that scrolls vertically (a stray vertical scroll bar)
    for (let a = c; a && a !== main; a = a.parentElement) {
      const oy = getComputedStyle(a).overflowY;
      if ((oy === "auto" || oy === "scroll") && a.scrollHeight > a.clientHeight + TOL
          && a.clientHeight < 600) {
        math.vertical.push(`${label(c)}: ${describe(a)} scrolls vertically (${a.scrollHeight} > ${a.clientHeight} px)`);
        break;
      }
    }
  }

  // --- punctuation after in-line maths on the formula's line, never starting the next
  // (wt-site.js glues them; a line that starts with the full stop of a sentence ending
  // in a formula is what a narrow screen shows otherwise)
  math.orphans = [];
  for (const c of main.querySelectorAll("mjx-container:not([display='true'])")) {
    const p = c.parentElement;
    const box = p && p.matches("span.math") && p.childNodes.length === 1 ? p : c;
    const next = box.nextSibling;
    if (!next || next.nodeType !== 3 || !/^[.,;:!?)]/.test(next.data)) continue;
    const range = document.createRange();
    range.setStart(next, 0); range.setEnd(next, 1);
    const q = range.getBoundingClientRect(), f = c.getBoundingClientRect();
    if (q.height > 0 && f.height > 0 && (q.top + q.bottom) / 2 > f.bottom)
      math.orphans.push(`${label(c)} then "${next.data.slice(0, 12)}"`);
  }

  // --- text outputs and tables: wrapped or scrolling, never cut
  const text = { checked: 0, cut: [] };
  for (const el of main.querySelectorAll("pre, table, .cell_output .output")) {
    const rect = el.tagName === "PRE" ? textRect(el) : unionOf([el]);
    if (!rect) continue;
    text.checked++;
    const why = cutBy(el, rect);
    if (why) text.cut.push(`${describe(el)} "${el.textContent.replace(/\s+/g, " ").trim().slice(0, 60)}": ${why}`);
  }

  // --- raw TeX in rendered text (outside maths, code and scripts)
  const SKIP = "mjx-container, script, style, pre, code, kbd, samp, textarea, .highlight, .math, mjx-assistive-mml";
  const BLOCK = "p, li, dd, dt, td, th, h1, h2, h3, h4, h5, h6, caption, figcaption, div, section";
  const blocks = new Map();
  const walker = document.createTreeWalker(main, NodeFilter.SHOW_TEXT);
  for (let n = walker.nextNode(); n; n = walker.nextNode()) {
    const p = n.parentElement;
    if (!p || p.closest(SKIP)) continue;
    const block = p.closest(BLOCK) || main;
    blocks.set(block, (blocks.get(block) || "") + n.data);
  }
  const TEX = /\\(?:frac|dfrac|dot|ddot|partial|begin|end|tilde|left|right|sqrt|mathrm|mathbf|operatorname|cdot|theta|varepsilon|epsilon|alpha|sigma|nu|tag|text)(?![A-Za-z])|\\[()[\]]|\$[^$\n]{1,300}\$|\$\$/g;
  const rawTex = [];
  for (const [block, s] of blocks) {
    const hits = s.match(TEX);
    if (hits) {
      const i = s.search(TEX);
      rawTex.push(`${describe(block)}: ${[...new Set(hits)].slice(0, 4).join(" ")} in "${s.slice(Math.max(0, i - 30), i + 50).replace(/\s+/g, " ")}"`);
    }
  }

  // --- the page itself must not scroll sideways
  const docEl = document.documentElement;
  const pageOverflow = docEl.scrollWidth > docEl.clientWidth + TOL
    ? `the page is ${docEl.scrollWidth} px wide in a ${docEl.clientWidth} px window` : null;

  return { math, text, rawTex, pageOverflow };
}
