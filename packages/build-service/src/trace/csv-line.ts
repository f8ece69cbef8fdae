/**
 * One line of the runtime's CSV log -> its fields (RFC 4180 quoting, as runtime/src/csvlog.c
 * writes it: a field holding a comma, quote or line break is quoted, quotes doubled).
 * Pure and total: any text gives fields, never an exception (a quoted field with no closing quote
 * runs to the line's end: splitCsvRecord tells such a line apart).
 */
export function splitCsvLine(line: string): string[] {
    return split(line).fields;
}

/**
 * splitCsvLine's fields, or undefined when a quoted field is not closed before the line ends: the
 * runtime never writes one, so the line was cut or forged, and is no record.
 */
export function splitCsvRecord(line: string): string[] | undefined {
    const { fields, closed } = split(line);
    return closed ? fields : undefined;
}

function split(line: string): { fields: string[]; closed: boolean } {
    if (!line.includes('"')) return { fields: line.split(','), closed: true }; // the common line: no quoted field
    const fields: string[] = [];
    let closed = true;
    let i = 0;
    while (i <= line.length) {
        if (line[i] === '"') {
            let value = '';
            let ended = false;
            i++;
            while (i < line.length) {
                if (line[i] === '"' && line[i + 1] === '"') { value += '"'; i += 2; }
                else if (line[i] === '"') { i++; ended = true; break; }
                else value += line[i++];
            }
            closed &&= ended;
            // text after a closing quote up to the comma belongs to the field (lenient)
            const end = line.indexOf(',', i);
            value += end < 0 ? line.slice(i) : line.slice(i, end);
            fields.push(value);
            i = end < 0 ? line.length + 1 : end + 1;
        } else {
            const end = line.indexOf(',', i);
            fields.push(end < 0 ? line.slice(i) : line.slice(i, end));
            i = end < 0 ? line.length + 1 : end + 1;
        }
    }
    return { fields, closed };
}

/**
 * A field of a CSV line as the runtime writes it: quoted when it holds a quote or a comma (quotes
 * doubled); a line break, which would end the record, written as a space.
 */
export function csvField(text: string): string {
    const one = /[\r\n]/.test(text) ? text.replace(/[\r\n]+/g, ' ') : text;
    return /[",]/.test(one) ? `"${one.replace(/"/g, '""')}"` : one;
}
