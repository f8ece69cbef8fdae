/**
 * The words of C text (a protected region's content), each with where it stands: code, comment or
 * string/character literal, and whether it is a member name (`x.name`, `p->name`). Used to find and
 * rewrite the uses of a renamed entity in user code (docs/codegen.md, "Renames"): only whole C
 * identifiers are words (`in_coordinates` is not found in `in_coordinates2` or `my_in_coordinates`),
 * numbers are skipped (`1e5` holds no word `e5`). One pass, linear in the text.
 */

export type WordContext = 'code' | 'comment' | 'string';

export interface CWord {
    word: string;
    /** Offset in the text. */
    offset: number;
    context: WordContext;
    /** In code, right after `.` or `->` (blanks between allowed): a member of a struct, not a variable. */
    member: boolean;
}

const isStart = (c: number) => (c >= 65 && c <= 90) || (c >= 97 && c <= 122) || c === 95;
const isPart = (c: number) => isStart(c) || (c >= 48 && c <= 57);

/** Words of text[from, to) that are not code (inside a comment or a literal). */
function wordsIn(text: string, from: number, to: number, context: WordContext, out: CWord[]): void {
    for (let i = from; i < to;) {
        if (isStart(text.charCodeAt(i)) && (i === from || !isPart(text.charCodeAt(i - 1)))) {
            let j = i + 1;
            while (j < to && isPart(text.charCodeAt(j))) j++;
            out.push({ word: text.slice(i, j), offset: i, context, member: false });
            i = j;
        } else i++;
    }
}

export function cWords(text: string): CWord[] {
    const out: CWord[] = [];
    /** Last non-blank code character before the current position ('' at the start). */
    let previous = '';
    let previous2 = '';
    const n = text.length;
    for (let i = 0; i < n;) {
        const c = text.charCodeAt(i);
        const ch = text[i]!;
        if (ch === '/' && text[i + 1] === '/') {
            let end = text.indexOf('\n', i);
            if (end === -1) end = n;
            wordsIn(text, i + 2, end, 'comment', out);
            i = end;
            continue;
        }
        if (ch === '/' && text[i + 1] === '*') {
            let end = text.indexOf('*/', i + 2);
            end = end === -1 ? n : end + 2;
            wordsIn(text, i + 2, end, 'comment', out);
            i = end;
            continue;
        }
        if (ch === '"' || ch === "'") {
            let j = i + 1;
            while (j < n && text[j] !== ch && text[j] !== '\n') j += text[j] === '\\' ? 2 : 1;
            const end = Math.min(n, j + 1);
            wordsIn(text, i + 1, Math.min(j, n), 'string', out);
            previous2 = previous;
            previous = ch;
            i = end;
            continue;
        }
        if (isStart(c)) {
            let j = i + 1;
            while (j < n && isPart(text.charCodeAt(j))) j++;
            const member = previous === '.' || (previous === '>' && previous2 === '-');
            out.push({ word: text.slice(i, j), offset: i, context: 'code', member });
            previous2 = previous;
            previous = 'a';
            i = j;
            continue;
        }
        if (c >= 48 && c <= 57) {
            // a number (pp-number): digits, letters, '.', and a sign after an exponent
            let j = i + 1;
            while (j < n && (isPart(text.charCodeAt(j)) || text[j] === '.' || ((text[j] === '+' || text[j] === '-') && /[eEpP]/.test(text[j - 1]!)))) j++;
            previous2 = previous;
            previous = '0';
            i = j;
            continue;
        }
        if (ch !== ' ' && ch !== '\t' && ch !== '\n' && ch !== '\r' && ch !== '\f' && ch !== '\v') {
            previous2 = previous;
            previous = ch;
        }
        i++;
    }
    return out;
}

/**
 * `text` with every use of identifier `from` in code (not a member name, not in a comment or a
 * literal) replaced by `to`; returns the new text and how many were replaced.
 */
export function renameIdentifier(text: string, from: string, to: string): { text: string; count: number } {
    let out = '';
    let cursor = 0;
    let count = 0;
    for (const w of cWords(text)) {
        if (w.context !== 'code' || w.member || w.word !== from) continue;
        out += text.slice(cursor, w.offset) + to;
        cursor = w.offset + from.length;
        count++;
    }
    return { text: out + text.slice(cursor), count };
}
