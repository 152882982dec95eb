// weave-cut serve: the live preview of a command's page. The form is the CLI's options; on
// every change (debounced) the query is checked by the command (/CMD/check: messages next to
// the fields, the command line, the recipe), then the preview is drawn (/CMD/preview.svg) and
// the kit made (/CMD/summary.json: its figures; the download then comes from the cache) and
// its woven 3-D model shown (/CMD/model.glb, in the kit page's viewer, static/viewer/). A newer
// change aborts the requests of the older one (AbortController).
"use strict";
(function () {
  const form = document.getElementById("form");
  if (!form) return;
  const command = form.dataset.command;
  const $ = (id) => document.getElementById(id);
  const preview = $("preview"), sheet = $("sheet"), status = $("status");
  const download = $("download"), cmdline = $("cmdline"), recipe = $("recipe");
  const figures = $("figures"), warnings = $("warnings"), model = $("model");
  let controller = null, timer = null, shownUrl = null, release = null;

  function clearModel() {
    if (release) release();
    release = null;
    model.replaceChildren(model.querySelector("template"));
    model.hidden = true;
  }

  async function showModel(qs, signal) {  // asked only of a kit with a model (no 404 logged)
    const url = `/${command}/model.glb?${qs}`;
    const got = await fetch(url, {signal});
    if (!got.ok || !window.WeaveCutViewer) return;
    const buffer = await got.arrayBuffer();
    const figure = model.querySelector("template").content.firstElementChild.cloneNode(true);
    figure.querySelector("a").href = url;
    model.append(figure);
    model.hidden = false;
    release = window.WeaveCutViewer(figure, buffer) || null;
  }

  function value(field) {
    const kind = field.dataset.kind, key = field.dataset.key;
    if (kind === "flag") {  // a box the form ticks at first (data-default "on") sends "off"
      const on = field.querySelector("input[type=checkbox]").checked;
      return on ? "on" : field.dataset.default === "on" ? "off" : "";
    }
    if (kind === "formats") {
      return [...field.querySelectorAll("input:checked")].map((c) => c.value).join(",");
    }
    if (kind === "preset") {
      const on = field.querySelector("input:checked");
      return on ? on.value : "";
    }
    const control = field.querySelector(`[name="${key}"]`);
    let v = control.value.trim();
    if (kind === "input" && !v.startsWith("upload:")) {
      const param = $("f-input-param").hidden ? "" : $("f-input-param").value.trim();
      if (param) v += ":" + param;
    }
    return v;
  }

  function drawn() {  // an uploaded drawing is the input
    const input = $("f-input");
    return Boolean(input && input.value.startsWith("upload:"));
  }

  function query() {
    const params = new URLSearchParams();
    for (const field of form.querySelectorAll(".field[data-key]")) {
      if (field.hidden) continue;  // counts only with (or without) a flag, as data-needs says
      const v = value(field);
      // a default the command does not use for a drawing (data-drawing) is sent when typed
      const given = v !== field.dataset.default || (drawn() && field.dataset.drawing);
      if (v !== "" && given) params.append(field.dataset.key, v);
    }
    return params.toString();
  }

  function showErrors(errors) {
    for (const p of form.querySelectorAll(".error")) { p.hidden = true; p.textContent = ""; }
    for (const c of form.querySelectorAll("[aria-invalid]")) c.removeAttribute("aria-invalid");
    for (const [key, message] of Object.entries(errors || {})) {
      const where = $("e-" + key) || $("e-form");
      where.textContent = message;
      where.hidden = false;
      const control = $("f-" + key);
      if (control) control.setAttribute("aria-invalid", "true");
      const more = where.closest("details");
      if (more) more.open = true;
    }
  }

  function say(text, bad) {
    status.textContent = text;
    status.classList.toggle("bad", !!bad);
  }

  async function refused(response) {
    const message = await response.text();
    const key = response.headers.get("X-Field");
    if (response.status === 400 || response.status === 422) {
      showErrors({[key || "form"]: message});
    }
    say(response.status === 503 ? "The server is busy; trying again shortly." : message, true);
    if (response.status === 503) {
      const wait = parseInt(response.headers.get("Retry-After") || "5", 10);
      timer = setTimeout(update, Math.min(wait, 30) * 1000);
    }
  }

  function showFigures(data) {
    figures.replaceChildren(...data.figures.map(([label, text]) => {
      const row = document.createElement("div");
      const dt = document.createElement("dt"), dd = document.createElement("dd");
      dt.textContent = label; dd.textContent = text;
      row.append(dt, dd);
      return row;
    }));
    warnings.replaceChildren(...data.warnings.map((w) => {
      const li = document.createElement("li");
      li.textContent = "Warning: " + w;
      return li;
    }));
  }

  async function update() {
    clearTimeout(timer);
    follow();  // an upload, or the page's first query: the fields its input takes
    if (controller) controller.abort();
    controller = new AbortController();
    const signal = controller.signal;
    const qs = query();
    history.replaceState(null, "", `/${command}${qs ? "?" + qs : ""}${location.hash}`);
    download.href = `/${command}.zip?${qs}`;
    try {
      const checked = await fetch(`/${command}/check?${qs}`, {signal});
      const found = await checked.json();
      showErrors(found.errors);
      cmdline.textContent = found.command_line || "";
      recipe.textContent = found.recipe || "";
      download.setAttribute("aria-disabled", String(!found.ok));
      if (!found.ok) { say("Fix the marked field to see the preview.", true); return; }
      sheet.classList.add("busy");
      say("Drawing the preview…");
      const drawn = await fetch(`/${command}/preview.svg?${qs}`, {signal});
      if (!drawn.ok) { sheet.classList.remove("busy"); return refused(drawn); }
      const url = URL.createObjectURL(await drawn.blob());
      preview.src = url;
      preview.dataset.query = qs;
      if (shownUrl) URL.revokeObjectURL(shownUrl);
      shownUrl = url;
      sheet.classList.remove("busy");
      say("Preview ready; making the kit…");
      figures.replaceChildren();
      clearModel();
      figures.classList.remove("made");
      warnings.replaceChildren();
      const made = await fetch(`/${command}/summary.json?${qs}`, {signal});
      if (!made.ok) return refused(made);
      const kit = await made.json();
      showFigures(kit);
      figures.classList.add("made");
      say("The kit is ready to download.");
      download.dataset.ready = qs;
      if (kit.model) await showModel(qs, signal);
    } catch (err) {
      if (err.name === "AbortError") return;
      sheet.classList.remove("busy");
      say("The server did not answer; is weave-cut serve still running?", true);
    }
  }

  function follow() {  // show a field only for the inputs it is for (data-not-for: the kind of
    // input the command refuses it for) and with (or without) the flag it needs; a hidden flag
    // is off (fields come in the command's order: a flag before the fields that need it)
    const input = $("f-input"), chosen = input && input.selectedOptions[0];
    const kind = (chosen && chosen.dataset.kind) || "";
    for (const field of form.querySelectorAll(".field[data-not-for], .field[data-needs]")) {
      let hidden = field.dataset.notFor === kind;
      const needs = field.dataset.needs, flag = needs && $("f-" + needs.replace("!", ""));
      if (flag) {
        const on = flag.checked && !flag.closest(".field").hidden;
        hidden = hidden || on === needs.startsWith("!");
      }
      field.hidden = hidden;
    }
    for (const help of form.querySelectorAll(".help[data-help]")) {  // no help names a field
      // this input's kit does not offer (data-help-KIND: the help without it)
      help.textContent = help.getAttribute("data-help-" + kind) ?? help.dataset.help;
    }
    for (const field of form.querySelectorAll(".field[data-drawing]")) {  // chosen for one
      const box = field.querySelector("input[type=text]");
      if (box) box.placeholder = drawn() ? field.dataset.drawing : field.dataset.default;
    }
  }

  function later() {
    follow();
    clearTimeout(timer);
    download.dataset.ready = "";
    timer = setTimeout(update, 350);
  }

  for (const select of form.querySelectorAll("select")) {  // the chosen item's description
    select.addEventListener("change", () => {
      const hint = $("h-" + select.name), chosen = select.selectedOptions[0];
      if (!hint || !chosen) return;
      let about = hint.querySelector(".about");
      if (!about) { about = document.createElement("span"); about.className = "about"; hint.prepend(about, " "); }
      about.textContent = chosen.dataset.description || "";
      const param = $("f-input-param");
      if (select.name === "input" && param) {
        param.hidden = !chosen.dataset.param;
        param.placeholder = chosen.dataset.param || "";
        if (param.hidden) param.value = "";
      }
    });
  }
  form.addEventListener("input", later);
  form.addEventListener("change", later);
  form.addEventListener("submit", (e) => { e.preventDefault(); update(); });

  const file = $("f-upload");
  if (file) {  // choosing a file is no change of the form: the upload's answer decides
    file.addEventListener("input", (e) => e.stopPropagation());
    file.addEventListener("change", async (e) => {
      e.stopPropagation();
      const chosen = file.files[0];
      if (!chosen) return;
      clearTimeout(timer);  // the upload's answer replaces what the form was drawing
      if (controller) controller.abort();
      sheet.classList.remove("busy");
      say(`Reading ${chosen.name}…`);
      try {
        const sent = await fetch("/upload", {method: "POST", body: chosen});
        if (!sent.ok) {
          showErrors({input: await sent.text()});
          say("The drawing was not accepted.", true);
          return;
        }
        const {id, kind} = await sent.json();
        const option = document.createElement("option");
        option.value = "upload:" + id;
        if (kind) option.dataset.kind = kind;  // a surface in space: a ball, as the CLI makes
        option.textContent = `${chosen.name} (your drawing)`;
        $("uploads").append(option);
        $("f-input").value = option.value;
        $("f-input-param").value = "";
        const more = $("drawing-options");
        if (more) more.open = true;
        update();
      } catch (err) {
        say("The upload failed; is weave-cut serve still running?", true);
      } finally {
        file.value = "";
      }
    });
  }
  if (location.hash === "#input" && file) file.focus();
  update();
})();
