// whittaker-teach course website (book/_ext/wt_site.py).
// After MathJax has typeset the page, every display equation that is wider
// than its column (its div.math box scrolls) gets the class `wt-wide`, a
// keyboard focus stop (arrow keys scroll it) and an accessible label; the
// marks are renewed when the window is resized.
(function () {
  "use strict";

  function markWide() {
    document.querySelectorAll("div.math").forEach(function (c) {
      var wide = c.scrollWidth > c.clientWidth + 1;
      c.classList.toggle("wt-wide", wide);
      if (wide) {
        c.setAttribute("tabindex", "0");
        c.setAttribute("role", "region");
        if (!c.hasAttribute("aria-label")) c.setAttribute("aria-label", "wide equation: scroll sideways to read all of it");
      } else if (c.getAttribute("tabindex") === "0") {
        c.removeAttribute("tabindex");
        c.removeAttribute("role");
      }
    });
  }

  function whenTypeset() {
    var mj = window.MathJax;
    if (mj && mj.startup && mj.startup.promise) {
      mj.startup.promise.then(markWide);
    } else {
      markWide();
    }
  }

  var timer = null;
  window.addEventListener("resize", function () {
    clearTimeout(timer);
    timer = setTimeout(markWide, 150);
  });
  if (document.readyState === "complete") whenTypeset();
  else window.addEventListener("load", whenTypeset);
})();
