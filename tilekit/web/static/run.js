// Live progress of a search run: server-sent events from /api/runs/ID/events.
(function () {
  "use strict";
  const root = document.getElementById("run");
  if (!root) return;
  const id = root.dataset.run;
  const terminal = ["done", "failed", "cancelled", "interrupted"];
  function show(info) {
    document.getElementById("status").textContent = info.status;
    document.getElementById("chunks").textContent = info.chunks_done + "/" + info.chunks_total;
    document.getElementById("rows").textContent = String(info.rows);
    document.getElementById("seconds").textContent = Number(info.seconds).toFixed(2);
    const total = Math.max(1, info.chunks_total);
    document.getElementById("progress").value = 100 * info.chunks_done / total;
    root.dataset.status = info.status;
  }
  if (terminal.indexOf(root.dataset.status) < 0 && window.EventSource) {
    const source = new EventSource("/api/runs/" + encodeURIComponent(id) + "/events");
    const started = root.dataset.status;
    source.addEventListener("progress", function (evt) { show(JSON.parse(evt.data)); });
    source.addEventListener("end", function (evt) {
      show(JSON.parse(evt.data)); source.close();
      if (started !== "done") window.location.reload();  // the results table is complete now
    });
    source.addEventListener("timeout", function () { source.close(); });
  }
  const cancel = document.getElementById("cancel");
  if (cancel) {
    cancel.addEventListener("click", function () {
      fetch("/api/runs/" + encodeURIComponent(id) + "/cancel", { method: "POST" })
        .then(function (r) { return r.json(); }).then(function (info) { if (info.status) show(info); });
    });
  }
})();
