// The multigrid offsets page (§6.3): one slider per grid offset gamma_j of the chosen record;
// every change re-renders through /api/render/NAME?set=gamma=g0,g1,... (the server refuses
// singular offsets with the reason).
(function () {
  "use strict";
  const root = document.getElementById("multigrid");
  if (!root) return;
  const view = document.getElementById("view");
  const errorBox = document.getElementById("error");
  const offsets = document.getElementById("offsets");
  const select = document.getElementById("tiling");
  let timer = null;

  function gammas() {
    return Array.from(offsets.querySelectorAll("input")).map(function (i) { return i.value; });
  }

  function query(extra) {
    return window.tilekitQuery(function (q) { q.set("set", "gamma=" + gammas().join(",")); }, extra);
  }

  const live = window.tilekitLive(root, view, errorBox);

  function render() {
    const name = select.value;
    root.dataset.gamma = gammas().join(",");
    live("/api/render/" + encodeURIComponent(name) + "?" + query({ format: "json", size: 720 }));
    document.getElementById("export-svg").href =
      "/api/render/" + encodeURIComponent(name) + "?" + query({ format: "svg", size: 800, download: 1 });
  }

  function later() { clearTimeout(timer); timer = setTimeout(render, 120); }

  function load() {
    fetch("/api/tiling/" + encodeURIComponent(select.value))
      .then(function (r) { return r.json(); })
      .then(function (body) {
        offsets.innerHTML = "";
        (body.spec.gamma || []).forEach(function (g, j) {
          const label = document.createElement("label");
          label.textContent = "gamma" + j + " ";
          const input = document.createElement("input");
          Object.assign(input, { type: "range", id: "gamma" + j, min: -1, max: 1, step: 0.001, value: g });
          const out = document.createElement("output");
          out.id = "gamma" + j + "-out";
          out.textContent = g;
          input.addEventListener("input", function () { out.textContent = input.value; later(); });
          label.append(input, out);
          offsets.append(label);
        });
        render();
      });
  }

  const extent = document.getElementById("extent");
  extent.addEventListener("input", function () {
    document.getElementById("extent-out").textContent = extent.value;
    later();
  });
  select.addEventListener("change", load);
  load();
})();
