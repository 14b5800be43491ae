/* rsm-lrg notebook profiler, in the notebook page: answers the profiler frames' requests for
 * the shared assets (plotly.js, the page's script and style) with the text of the
 * <script type="text/plain" data-rsm-lrg-asset="SHA"> blocks that the first profiler of the
 * kernel session carried (never run here; kept once the first frame asked for them). */
(function () {
  "use strict";
  if (window.rsmLrgAssetHost) return;
  var cache = Object.create(null);
  window.rsmLrgAssetHost = cache;
  function find(sha) {
    if (typeof sha !== "string") return undefined;
    if (!(sha in cache)) {
      var blocks = document.querySelectorAll("script[data-rsm-lrg-asset]");
      for (var i = 0; i < blocks.length; i++) {
        if (blocks[i].getAttribute("data-rsm-lrg-asset") === sha) { cache[sha] = blocks[i].textContent; break; }
      }
    }
    return cache[sha];
  }
  window.addEventListener("message", function (ev) {
    var d = ev.data;
    if (!d || d.type !== "rsm-lrg-assets-request" || !Array.isArray(d.need) || !ev.source) return;
    var out = Object.create(null);
    for (var i = 0; i < d.need.length; i++) {
      var t = find(d.need[i]);
      if (t === undefined) return;  /* not (yet) in this page: the frame asks again */
      out[d.need[i]] = t;
    }
    ev.source.postMessage({type: "rsm-lrg-assets", assets: out}, "*");
  });
})();
