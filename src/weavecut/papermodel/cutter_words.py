"""The words of a print-and-cut book (``printcut``): where the registration marks are, which
cut file (and print image) belongs to which strip page, and how the cutter's software puts the
page and its cut file together, page 1's sources and page 2's first steps; a cutter whose
software prints its own marks (Cricut Design Space) has words of its own."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

from .modules import copy_letter
from .printcut import BLEED, Cutter
from .wording import PRINTED, Words, page_index


def marks_text(machine: Cutter) -> str:
    """The registration marks of ``machine`` in words ("a 5 mm square top-left and L corners
    top-right and bottom-left, 10 mm from the edges")."""
    where = f"{machine.inset:g} mm from the page's edges"
    if machine.marks == "frame":
        return f"a black frame {where}"
    if machine.marks == "corners":
        return f"L corners ({machine.length:g} mm arms) at the four corners, {where}"
    return (f"a {machine.length:g} mm square top-left and L corners top-right and bottom-left, "
            f"{where}")


def _strip_pages(book) -> tuple[str, str]:
    """("p. 3-8", how many times to make them: "once", or once per direction for a module
    printed per copy)."""
    strips = f"p. {book.strip_pages[0]}" + (f"-{book.strip_pages[-1]}"
                                             if len(book.strip_pages) > 1 else "")
    k = book.plan.k
    times = (f"{k} times, once per direction (write the copy letter, A to "
             f"{copy_letter(k - 1)}, on the back of each strip)" if book.layout == "module"
             and k > 1 else "once")
    return strips, times


def _design_space_words(machine: Cutter, output: Path) -> Words:
    """The words of a kit whose cutter's software prints its own marks (Cricut): the strip
    pages show what each page holds; Design Space prints each page's print image with its
    sensor marks and cuts round it. Sources: help.cricut.com articles 360009387274 ("How to
    Print Then Cut in Design Space": upload, Flatten, Make it, Design Space prints the marks)
    and 360009429814 ("How large can I Print Then Cut?": 6.75 x 9.25 in is the area every
    machine and paper takes; newer machines take more, on an area that is not a rectangle)."""
    name, stem = machine.title, output.stem
    w, h = (v / 25.4 for v in machine.max_size) if machine.max_size else (6.75, 9.25)

    def sources(book) -> str:
        strips, times = _strip_pages(book)
        return (f"Print then cut ({name}): Design Space prints each strip page itself, with its "
                "own sensor marks round it, and cuts only pages it printed, so do not print "
                f"the strip pages of this PDF ({strips}) to cut them: they show what each page "
                f"holds. Beside this PDF each strip page has its print image "
                f"({stem}-pNN-print.svg, NN the page number: its strips as printed, within "
                f"{w:g} x {h:g} in, the largest image every Cricut prints then cuts) and its "
                f"cut file ({stem}-pNN-cut.svg or .dxf, the outlines alone). Make each page "
                f"{times}. Where each strip is: {page_index(book)}.")

    return replace(PRINTED, cut_line=False,
                   scale=" Design Space prints at 100 %: keep its print dialog at actual size.",
                   sources=sources,
                   need=f"You need: your {name} cutter with its mat, a printer Design Space "
                        "prints to, tape or paper clips, a glue stick and a piece of cardboard "
                        "a little larger than the model.",
                   cut=f"Cut each strip page with the cutter: in Design Space upload its print "
                       f"image ({stem}-pNN-print.svg), select all its layers and Flatten them "
                       "(one Print Then Cut image, cut round the strips' outlines), keep its "
                       "size (the strips at 100 %), and Make it: Design Space prints it with "
                       "its sensor marks (bleed on), the machine reads the marks and cuts round "
                       "every strip. Sort the strips by ID: the ID printed in the strip's own "
                       "colour is its name on page 1; a small ID in a light part names the "
                       "strand that lies on top there.")


def cutter_words(machine: Cutter, output: Path) -> Words:
    """The print-and-cut book's words: the strip pages carry registration marks, each strip
    page's cut file lies beside the PDF ``output``, and how the cutter's software puts the two
    together (page 1's sources, page 2's first steps); a cutter whose software prints its own
    marks has words of its own (:func:`_design_space_words`)."""
    if machine.own_marks:
        return _design_space_words(machine, output)
    name, stem = machine.title, output.stem

    def files(book) -> str:
        first, last = book.strip_pages[0], book.strip_pages[-1]
        one = f"{stem}-p{first:02d}-cut.svg or .dxf"
        return one if first == last else (f"{one} for page {first}, and so on to "
                                           f"{stem}-p{last:02d}-cut for page {last}")

    def sources(book) -> str:
        strips, times = _strip_pages(book)
        return (f"Print and cut ({name}): print the strip pages ({strips}) {times}. Each carries "
                f"registration marks ({marks_text(machine)}) that the cutter's eye reads to "
                f"find the page, and has its cut file beside this PDF ({files(book)}): the "
                "outlines of its strips, at the page's size. No cut line is printed: each "
                f"strip's colours reach {BLEED:g} mm past where the cutter cuts, so a cut a "
                f"little off leaves no white edge. Where each strip is: {page_index(book)}.")

    return replace(PRINTED, cut_line=False,
                   scale=" Print at 100 % (no fit to page), marks and all.",
                   sources=sources,
                   need=f"You need: the printed strip pages, your {name} cutter with its mat, "
                        "tape or paper clips, a glue stick and a piece of cardboard a little "
                        "larger than the model.",
                   cut="Cut each strip page with the cutter: in its software, open its cut file "
                       f"({stem}-pNN-cut.dxf, NN the page number, beside this PDF: every edition "
                       "opens DXF, Silhouette Studio's free Basic Edition too; the .svg needs "
                       "one that reads SVG, such as Studio's Designer Edition). The DXF's origin "
                       "(0, 0) is the page's bottom-left corner and its limits and extents are "
                       "the page, and the SVG is the page's size: put either at the page's "
                       "corner and its lines lie round the printed strips. Turn on the software's "
                       f"registration marks as page 1 gives them ({marks_text(machine)}), so "
                       "they lie on the printed ones; put the printed page on the mat, let the "
                       "cutter read the marks, and cut. " + PRINTED.cut.partition(". ")[2])


def cut_file_note(output: Path, machine: Cutter | None = None):
    """A strip page's subtitle note, in one line: its cut file's name, and its print image's
    where the cutter's software prints the marks (``page_note`` of ``strand_book``)."""
    if machine is not None and machine.own_marks:
        return lambda n: (f"Print image: {output.stem}-p{n:02d}-print.svg; cut file: "
                          f"{output.stem}-p{n:02d}-cut.svg / .dxf.")
    return lambda n: f"Cut file: {output.stem}-p{n:02d}-cut.svg / .dxf, beside this PDF."
