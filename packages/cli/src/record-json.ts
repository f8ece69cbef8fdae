/**
 * Trace records as JSON lines, byte for byte `escapeControls(JSON.stringify(record)) + '\n'` (the
 * spelling of `contract trace --format json`, of `contract run --trace` as the run goes, and of
 * the check that settles the file at its end: the three must give the same bytes), written as
 * UTF-8 straight into a buffer instead of strings joined and escaped afterwards. A long run is
 * millions of records: the general path (a string per value, their concatenation, a regular
 * expression over every line, the text encoded again to be hashed or written) was most of the
 * end of `contract run --trace`, and its garbage most of the rest.
 *
 * Each string is scanned once as it is copied: one that holds only printable ASCII but `"` and
 * `\` (nearly every field of a runtime log) is the same text in JSON and is written as it is; any
 * other string goes the general way (JSON.stringify, then escapeControls), and so does a record
 * holding anything that is not plain data (a toJSON, a bigint, a boxed value, an object of a class).
 *
 * A record's `fields` (the object under the key `fields` of the line's object) is written with
 * each key's one JSON type (build-service trace/field-types.ts): a number key's value as a JSON
 * number with its exact digits, also past 15 digits where the reader keeps them as text
 * (`"tick_ns":9123357357727918`), a string key's value as a string (`"value":"12"`). JSON.stringify
 * would write the reader's types (a number up to 15 digits, a string beyond): jsonTypedFields gives
 * the value that general path must be given to write the same bytes.
 */
import { fieldJsonType } from '@contract-studio/build-service/trace';
import { escapeControls } from './terminal-text.js';

/** A character JSON.stringify or escapeControls writes otherwise than as itself: a control, `"`, `\`, DEL, anything past ASCII. */
const NEEDS_GENERAL_PATH = /[^\x20\x21\x23-\x5b\x5d-\x7e]/;
/** Strings of this many characters or more are checked by NEEDS_GENERAL_PATH and copied in one call, shorter ones character by character. */
const LONG_STRING = 40;

/** Thrown where a value is not plain data: the whole record is then written the general way. */
const NOT_PLAIN = Symbol('not plain data');

/** The bytes of JSON lines, appended record by record (`add`), then taken (`take`, `text`). */
export class JsonLines {
    private buf: Buffer;
    private pos = 0;

    constructor(private readonly initialBytes = 64 * 1024) {
        this.buf = Buffer.allocUnsafe(initialBytes);
    }

    /** Bytes written and not taken yet. */
    get length(): number {
        return this.pos;
    }

    /** Appends `record` as one JSON line, its newline included. */
    add(record: object): void {
        const start = this.pos;
        try {
            if (typeof record === 'object' && record !== null && !Array.isArray(record)) this.object(record, true);
            else this.value(record);
        } catch (e) {
            this.pos = start;
            if (e !== NOT_PLAIN) throw e;
            this.utf8(escapeControls(JSON.stringify(record)));
        }
        this.room(1);
        this.buf[this.pos++] = 10;
    }

    /** The bytes written (a buffer of its own), the writer emptied. */
    take(): Buffer {
        const out = this.buf.subarray(0, this.pos);
        this.buf = Buffer.allocUnsafe(Math.max(this.initialBytes, this.pos));
        this.pos = 0;
        return out;
    }

    /** The text written (UTF-8 decoded: every string was written whole, so it decodes to what was written), the writer emptied. */
    text(): string {
        const out = this.buf.toString('utf8', 0, this.pos);
        this.pos = 0;
        return out;
    }

    private room(bytes: number): void {
        if (this.pos + bytes <= this.buf.length) return;
        const grown = Buffer.allocUnsafe(Math.max(this.buf.length * 2, this.pos + bytes));
        this.buf.copy(grown, 0, 0, this.pos);
        this.buf = grown;
    }

    private utf8(text: string): void {
        this.room(3 * text.length);
        this.pos += this.buf.write(text, this.pos, 'utf8');
    }

    /** ASCII text known to need no escape (a number's digits, punctuation). */
    private ascii(text: string): void {
        this.room(text.length);
        const buf = this.buf;
        let p = this.pos;
        for (let i = 0; i < text.length; i++) buf[p++] = text.charCodeAt(i);
        this.pos = p;
    }

    /** A safe integer >= 0 (-0 too: JSON writes it `0`) in decimal, as String writes it. */
    private digits(n: number): void {
        let width = 1;
        for (let t = n; t >= 10; t = Math.floor(t / 10)) width++;
        this.room(width);
        const buf = this.buf;
        let p = this.pos + width;
        this.pos = p;
        do {
            const q = Math.floor(n / 10);
            buf[--p] = 48 + n - q * 10;
            n = q;
        } while (n > 0);
    }

    /** `s` as a JSON string: copied as it is while it holds nothing to escape, else the general way. */
    private string(s: string): void {
        const n = s.length;
        if (n >= LONG_STRING) {
            if (NEEDS_GENERAL_PATH.test(s)) return this.utf8(escapeControls(JSON.stringify(s)));
            this.room(n + 2);
            this.buf[this.pos] = 34;
            this.buf.write(s, this.pos + 1, 'latin1');
            this.buf[this.pos + n + 1] = 34;
            this.pos += n + 2;
            return;
        }
        this.room(n + 2);
        const buf = this.buf;
        let p = this.pos;
        buf[p++] = 34; // "
        for (let i = 0; i < n; i++) {
            const c = s.charCodeAt(i);
            // a control, `"`, `\`, DEL and every character past ASCII: JSON.stringify and escapeControls decide
            if (c < 0x20 || c > 0x7e || c === 0x22 || c === 0x5c) {
                this.utf8(escapeControls(JSON.stringify(s)));
                return;
            }
            buf[p++] = c;
        }
        buf[p++] = 34;
        this.pos = p;
    }

    /** `v` written as JSON.stringify writes it (the caller leaves out what it leaves out: `omitted`). */
    private value(v: unknown): void {
        switch (typeof v) {
            case 'string':
                return this.string(v);
            case 'number':
                if (Number.isSafeInteger(v) && v >= 0) return this.digits(v);
                return this.ascii(Number.isFinite(v) ? String(v) : 'null');
            case 'boolean':
                return this.ascii(v ? 'true' : 'false');
            case 'object':
                if (v === null) return this.ascii('null');
                if (Array.isArray(v)) return this.array(v);
                return this.object(v);
            default:
                throw NOT_PLAIN; // a bigint (JSON.stringify throws), or undefined, a function, a symbol at the top
        }
    }

    private array(a: unknown[]): void {
        if (Object.getPrototypeOf(a) !== Array.prototype || typeof (a as { toJSON?: unknown }).toJSON === 'function') throw NOT_PLAIN;
        this.ascii('[');
        for (let i = 0; i < a.length; i++) {
            if (i) this.ascii(',');
            const v = a[i];
            if (omitted(v)) this.ascii('null');
            else this.value(v);
        }
        this.ascii(']');
    }

    /**
     * `o` as JSON.stringify writes it; `top`: a record, whose `fields` is written `typed`: each value
     * with its key's JSON type (fieldJsonValue: an integer's exact digits), other keys as they are.
     */
    private object(o: object, top = false, typed = false): void {
        const proto = Object.getPrototypeOf(o) as unknown;
        if ((proto !== Object.prototype && proto !== null) || typeof (o as { toJSON?: unknown }).toJSON === 'function') throw NOT_PLAIN;
        this.ascii('{');
        let first = true;
        // its own enumerable string keys, in JSON.stringify's order (for-in gives them in that
        // order, then inherited ones, left out; unlike Object.keys it makes no array of them)
        for (const key in o) {
            if (!hasOwn.call(o, key)) continue;
            const raw = (o as Record<string, unknown>)[key];
            const v = typed ? fieldJsonValue(key, raw) : raw;
            if (omitted(v)) continue;
            if (!first) this.ascii(',');
            first = false;
            this.string(key);
            this.ascii(':');
            if (v instanceof ExactDigits) this.ascii(v.digits);
            else if (top && key === 'fields' && typeof v === 'object' && v !== null && !Array.isArray(v)) this.object(v, false, true);
            else this.value(v);
        }
        this.ascii('}');
    }
}

const hasOwn = Object.prototype.hasOwnProperty;

/** An integer's exact decimal digits, written as a JSON number as they are. */
class ExactDigits {
    constructor(readonly digits: string) {}
}

/** `-?\d+`: an integer's text, of any length (the reader keeps one past 15 digits as this text). */
const INTEGER_TEXT = /^-?\d+$/;

/**
 * A `fields` value as its key's JSON type writes it: a number key's integer (a number, or the
 * digits the reader kept as text) as its exact digits (no leading zeros: JSON has none), a number
 * key's other word (not an integer: a forged line) left out (undefined); a string key's number as
 * its text. A key of no known type is written as it is.
 */
function fieldJsonValue(key: string, v: unknown): unknown {
    const type = fieldJsonType(key);
    if (type === 'number') {
        if (typeof v === 'number') return Number.isFinite(v) ? v : undefined;
        if (typeof v !== 'string' || !INTEGER_TEXT.test(v)) return undefined;
        const negative = v.charCodeAt(0) === 45;
        const digits = v.slice(negative ? 1 : 0).replace(/^0+(?=\d)/, '');
        return new ExactDigits(negative && digits !== '0' ? `-${digits}` : digits);
    }
    if (type === 'string' && typeof v === 'number') return String(v);
    return v;
}

/**
 * A record's `fields` as jsonTypedFields: the object JSON.stringify must be given to write what
 * JsonLines writes, its exact digits past 2^53 as BigInt (JSON.stringify cannot write those: a test
 * writes them with its own replacer); for tests and readers of the rule.
 */
export function jsonTypedFields(fields: Record<string, unknown>): Record<string, unknown> {
    const out: Record<string, unknown> = {};
    for (const key of Object.keys(fields)) {
        const v = fieldJsonValue(key, fields[key]);
        if (v === undefined) continue;
        out[key] = v instanceof ExactDigits ? BigInt(v.digits) : v;
    }
    return out;
}

/** A property JSON.stringify leaves out of an object (an array's element of that kind is `null`). */
function omitted(v: unknown): boolean {
    const t = typeof v;
    return t === 'undefined' || t === 'function' || t === 'symbol';
}

const one = new JsonLines(4096);

/** A record as one line of JSON, without its newline: escapeControls(JSON.stringify(record)). */
export function recordJson(record: object): string {
    one.add(record);
    return one.text().slice(0, -1);
}

/** Records as JSON lines, each ended by its newline (none for no record). */
export function recordsJson(records: readonly object[]): string {
    for (const r of records) one.add(r);
    return one.text();
}
