// Live pictures for the pages that re-render as sliders move (the plugins' editors): one
// request at a time wins (older answers are dropped), the SVG fills the view, a refusal shows
// the server's one-line reason and keeps the last picture. The root element's data-state
// (ok / refused) and data-renders (a count) are what the browser tests wait on.
// The returned promise gives true when the picture was drawn (a page updates its export links
// then, so they always name the last tiling drawn), false when refused, null when superseded.
window.tilekitLive = function (root, view, errorBox) {
  "use strict";
  let seq = 0;
  return function render(url) {
    const mine = ++seq;
    return fetch(url)
      .then(function (r) { return r.json().then(function (b) { return { ok: r.ok, body: b }; }); })
      .then(function (res) {
        if (mine !== seq) return null;
        if (!res.ok) {
          errorBox.textContent = res.body.error || "render failed";
          root.dataset.state = "refused";
          return false;
        }
        errorBox.textContent = "";
        view.innerHTML = res.body.svg;
        const svg = view.querySelector("svg");
        if (svg) { svg.removeAttribute("width"); svg.removeAttribute("height"); }
        root.dataset.state = "ok";
        root.dataset.renders = String(Number(root.dataset.renders || 0) + 1);
        return true;
      });
  };
};

// A render query: the page's own options (``fill(q)``), the square of half-width #extent as
// the region, then ``extra`` (format, size, download).
window.tilekitQuery = function (fill, extra) {
  "use strict";
  const q = new URLSearchParams();
  fill(q);
  const e = Number(document.getElementById("extent").value);
  q.set("region", [-e, -e, e, e].join(","));
  Object.keys(extra || {}).forEach(function (k) { q.set(k, extra[k]); });
  return q;
};
