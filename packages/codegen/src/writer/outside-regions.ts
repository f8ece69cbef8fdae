import { parseRegions } from '../regions/parse-regions.js';

/**
 * Code outside the protected regions when nothing records what the generator wrote there: no
 * manifest (deleted, or a tree from elsewhere), one written before skeleton records, one that
 * cannot be read (git conflict markers), or no record of that file. The file's text outside its
 * regions is compared with the regenerated file's (the fresh output, regions filled with the
 * user's code), line by line:
 * - whitespace is no text: a re-indented or re-spaced line, an older generator's spacing, blank
 *   lines added or removed are not the user's code;
 * - a region stands for nothing: its content is the merge's business (kept, or orphaned when its ID
 *   vanished), and a region the regenerated file adds or drops is no line of the user's;
 * - a line of the file is kept when the regenerated file holds it (as many times), wherever it is:
 *   generated lines moved, or removed by the user, lose no code.
 * What is left are the lines a regeneration would lose: the user's, or an older generator's that
 * differ from today's by more than whitespace (nothing tells them apart without a record).
 */

/** The non-blank lines of `text` outside its regions' contents, whitespace removed, each with its 1-based line in the file. */
function textOutsideRegions(text: string, file: string): { text: string; line: number }[] {
    const out: { text: string; line: number }[] = [];
    let line = 1;
    let current = '';
    let startLine = 1;
    const addText = (from: number, to: number) => {
        let i = from;
        for (let nl = text.indexOf('\n', i); nl >= 0 && nl < to; nl = text.indexOf('\n', i)) {
            current += text.slice(i, nl).replace(/\s+/g, '');
            if (current !== '') out.push({ text: current, line: startLine });
            current = '';
            line++;
            startLine = line;
            i = nl + 1;
        }
        current += text.slice(i, to).replace(/\s+/g, '');
    };
    let cursor = 0;
    for (const r of parseRegions(text, file).regions) {
        addText(cursor, r.start);
        for (let i = text.indexOf('\n', r.start); i >= 0 && i < r.end; i = text.indexOf('\n', i + 1)) line++;
        cursor = r.end;
    }
    addText(cursor, text.length);
    if (current !== '') out.push({ text: current, line: startLine });
    return out;
}

/**
 * The 1-based lines of `existing` (ascending) whose text outside the regions `regenerated` does not
 * hold, whitespace aside (see above). Throws RegionSyntaxError on a malformed `existing`.
 */
export function linesNotRegenerated(existing: string, regenerated: string, file: string): number[] {
    const available = new Map<string, number>();
    for (const l of textOutsideRegions(regenerated, `${file} (generated output)`)) available.set(l.text, (available.get(l.text) ?? 0) + 1);
    const lost: number[] = [];
    for (const l of textOutsideRegions(existing, file)) {
        const left = available.get(l.text) ?? 0;
        if (left > 0) available.set(l.text, left - 1);
        else if (lost[lost.length - 1] !== l.line) lost.push(l.line);
    }
    return lost;
}
