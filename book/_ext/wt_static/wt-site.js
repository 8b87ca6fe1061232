// whittaker-teach course website (book/_ext/wt_site.py).
// After MathJax has typeset the page, every display equation that is wider
// than its column (its div.math box scrolls) gets the class `wt-wide`, the
// classes `wt-at-start`/`wt-at-end` while it is scrolled to an edge (the CSS
// shades the edges beyond which more of it lies), a keyboard focus stop
// (arrow keys scroll it) and an accessible label. The marks follow every
// change of the box's size: window resized, a fold opened.
// In-line maths is also glued to the punctuation that touches it (a `.` or `,`
// after it, a `(` before it), so that a narrow screen never starts a line with
// the full stop of a sentence that ends in a formula.
(function () {
  "use strict";

  function markEdges(c) {
    c.classList.toggle("wt-at-start", c.scrollLeft <= 1);
    c.classList.toggle("wt-at-end", c.scrollLeft + c.clientWidth >= c.scrollWidth - 1);
  }

  function onScroll(event) {
    markEdges(event.currentTarget);
  }

  function markOne(c) {
    var wide = c.clientWidth > 0 && c.scrollWidth > c.clientWidth + 1;
    c.classList.toggle("wt-wide", wide);
    if (wide) {
      markEdges(c);
      if (!c.dataset.wtScroll) {
        c.addEventListener("scroll", onScroll, { passive: true });
        c.dataset.wtScroll = "1";
      }
      c.setAttribute("tabindex", "0");
      c.setAttribute("role", "region");
      if (!c.hasAttribute("aria-label")) c.setAttribute("aria-label", "wide equation: scroll sideways to read all of it");
    } else if (c.getAttribute("tabindex") === "0") {
      c.removeAttribute("tabindex");
      c.removeAttribute("role");
      c.removeAttribute("aria-label");
    }
  }

  function markAll() {
    var boxes = document.querySelectorAll("div.math");
    boxes.forEach(markOne);
    if (window.ResizeObserver) {
      var observer = new ResizeObserver(function (entries) {
        entries.forEach(function (entry) { markOne(entry.target); });
      });
      boxes.forEach(function (c) { observer.observe(c); });
    }
  }

  var AFTER = /^[.,;:!?)\]\u2019\u201d]+/, BEFORE = /[(\[\u2018\u201c]+$/;

  function glue(m) {
    // the formula's own box: MyST's span.math around MathJax's container, if there is one
    var p = m.parentNode;
    var c = p && p.nodeName === "SPAN" && p.classList.contains("math") &&
      p.childNodes.length === 1 ? p : m;
    var next = c.nextSibling, prev = c.previousSibling;
    var tail = next && next.nodeType === 3 ? next.data.match(AFTER) : null;
    var head = prev && prev.nodeType === 3 ? prev.data.match(BEFORE) : null;
    if (!tail && !head) return;
    var span = document.createElement("span");
    span.className = "wt-nobreak";
    c.parentNode.insertBefore(span, c);
    if (head) {
      prev.data = prev.data.slice(0, prev.data.length - head[0].length);
      span.appendChild(document.createTextNode(head[0]));
    }
    span.appendChild(c);
    if (tail) {
      next.data = next.data.slice(tail[0].length);
      span.appendChild(document.createTextNode(tail[0]));
    }
  }

  function keepPunctuation() {
    document.querySelectorAll("mjx-container:not([display='true'])").forEach(glue);
  }

  function afterTypeset() {
    keepPunctuation();
    markAll();
  }

  function whenTypeset() {
    var mj = window.MathJax;
    if (mj && mj.startup && mj.startup.promise) {
      mj.startup.promise.then(afterTypeset);
    } else {
      afterTypeset();
    }
  }

  if (document.readyState === "complete") whenTypeset();
  else window.addEventListener("load", whenTypeset);
})();
