/* weave-cut's 3-D viewer: every <figure class="model3d"> of the page shows the glTF binary
   embedded in it (base64, so the page works from file://, where a browser refuses to fetch
   files) with three.js (window.WeaveCutThree, three.min.js). Drag to turn, wheel or pinch to
   zoom, right-drag or two fingers to move; the button puts the view back. The figure's
   data-state becomes "ready" once the model is drawn ("error" if it could not be).
   window.WeaveCutViewer(figure, buffer) shows a model fetched by a page (weave-cut serve) in a
   figure added later; it answers a function that frees the figure's WebGL context. */
(function () {
  "use strict";
  var T = window.WeaveCutThree;

  function bytes(text) {
    var raw = atob(text.replace(/\s+/g, "")), out = new Uint8Array(raw.length);
    for (var i = 0; i < raw.length; i++) out[i] = raw.charCodeAt(i);
    return out.buffer;
  }

  function show(figure, buffer) {
    var canvas = figure.querySelector("canvas");
    var data = figure.querySelector("script[type='model/gltf-binary']");
    var button = figure.querySelector("button");
    if (!T || !canvas || !(data || buffer)) { figure.dataset.state = "error"; return; }
    var renderer;
    try {
      renderer = new T.WebGLRenderer({canvas: canvas, antialias: true,
                                      preserveDrawingBuffer: true});
    } catch (e) {
      figure.dataset.state = "error";
      figure.classList.add("nowebgl");
      return;
    }
    renderer.setPixelRatio(Math.min(window.devicePixelRatio || 1, 2));
    var scene = new T.Scene();
    scene.background = new T.Color("#ffffff");
    scene.add(new T.HemisphereLight(0xffffff, 0x70757a, 1.5));
    var camera = new T.PerspectiveCamera(30, 4 / 3, 0.001, 100);
    var sun = new T.DirectionalLight(0xffffff, 2.2);
    sun.position.set(-1, 1.5, 2);  // over the viewer's left shoulder, turning with the view
    camera.add(sun);
    scene.add(camera);
    var controls = new T.OrbitControls(camera, canvas);
    var draw = function () { renderer.render(scene, camera); };
    controls.addEventListener("change", draw);

    function fit() {
      var w = canvas.clientWidth, h = canvas.clientHeight;
      if (!w || !h) return;
      renderer.setSize(w, h, false);
      camera.aspect = w / h;
      camera.updateProjectionMatrix();
      draw();
    }
    new ResizeObserver(fit).observe(canvas);

    function failed(error) {
      figure.dataset.state = "error";
      console.error("weave-cut viewer: " + error);
    }
    try {
      new T.GLTFLoader().parse(buffer || bytes(data.textContent), "", loaded, failed);
    } catch (error) {
      failed(error);
    }

    function loaded(gltf) {
      scene.add(gltf.scene);
      var box = new T.Box3().setFromObject(gltf.scene);
      var centre = box.getCenter(new T.Vector3());
      var size = box.getSize(new T.Vector3());
      var radius = Math.max(size.x, size.y, size.z) / 2 * 1.1;
      var distance = radius / Math.sin(camera.fov * Math.PI / 360) * 1.02;
      var flat = size.y < 0.1 * radius;  // a flat model: seen from above
      var look = flat ? new T.Vector3(0, 3, 1) : new T.Vector3(0.35, 0.35, 1);
      camera.position.copy(centre).add(look.normalize().multiplyScalar(distance));
      camera.near = distance / 50;
      camera.far = distance * 10;
      camera.updateProjectionMatrix();
      controls.target.copy(centre);
      controls.minDistance = radius * 0.05;
      controls.maxDistance = distance * 4;
      controls.update();
      controls.saveState();
      if (button) button.addEventListener("click", function () { controls.reset(); });
      fit();
      draw();
      figure.dataset.state = "ready";
    }
    return function () { controls.dispose(); renderer.dispose(); renderer.forceContextLoss(); };
  }

  window.WeaveCutViewer = show;
  document.querySelectorAll("figure.model3d").forEach(function (f) { show(f); });
})();
