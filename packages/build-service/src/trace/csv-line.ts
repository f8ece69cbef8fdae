/**
 * One line of the runtime's CSV log -> its fields (RFC 4180 quoting, as runtime/src/csvlog.c
 * writes it: a field holding a comma, quote or line break is quoted, quotes doubled).
 * Pure and total: any text gives fields, never an exception.
 */
export function splitCsvLine(line: string): string[] {
    if (!line.includes('"')) return line.split(','); // the common line: no quoted field
    const fields: string[] = [];
    let i = 0;
    while (i <= line.length) {
        if (line[i] === '"') {
            let value = '';
            i++;
            while (i < line.length) {
                if (line[i] === '"' && line[i + 1] === '"') { value += '"'; i += 2; }
                else if (line[i] === '"') { i++; break; }
                else value += line[i++];
            }
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
    return fields;
}

/**
 * A field of a CSV line as the runtime writes it: quoted when it holds a quote or a comma (quotes
 * doubled); a line break, which would end the record, written as a space.
 */
export function csvField(text: string): string {
    const one = /[\r\n]/.test(text) ? text.replace(/[\r\n]+/g, ' ') : text;
    return /[",]/.test(one) ? `"${one.replace(/"/g, '""')}"` : one;
}
