package io.etherware.examples.bench;

import java.util.Objects;

/**
 * One line of the report: a measurement of one variant (Etherware-RT or a baseline) under one
 * condition. Latency rows carry {@link Percentiles}; rate and size rows carry a single
 * {@link #value()} in {@link #valueUnit()}; a row that could not be measured says why in
 * {@link #note()} and has {@link #measured()} false. Immutable.
 *
 * @param id          stable identifier, e.g. {@code dispatch.rt.flood}; the smoke test and the JSON use it
 * @param section     report section, e.g. {@code 2. HIGH dispatch latency}
 * @param variant     what was measured, e.g. {@code RealtimeScheduler} or {@code ArrayBlockingQueue hand-off}
 * @param condition   the load, e.g. {@code idle}, {@code LOW flood}
 * @param unit        the unit the percentiles are printed in: {@code us} or {@code ns}
 * @param percentiles the distribution, {@link Percentiles#NONE} for a value row
 * @param value       the row's single figure (rate, bytes), {@code NaN} if none
 * @param valueUnit   its unit, e.g. {@code msg/s}, {@code B/op}; empty if none
 * @param measured    false if the row could not be measured (the note says why)
 * @param aim         the aim this row is held to, empty if none
 * @param verdict     {@code met}, {@code missed} or empty
 * @param note        anything the reader needs (how counted, why not measured)
 */
public record BenchRow(String id, String section, String variant, String condition, String unit,
                       Percentiles percentiles, double value, String valueUnit, boolean measured, String aim,
                       String verdict, String note) {

    /** Requires the identifying fields. */
    public BenchRow {
        Objects.requireNonNull(id, "id");
        Objects.requireNonNull(section, "section");
        Objects.requireNonNull(variant, "variant");
        Objects.requireNonNull(condition, "condition");
        Objects.requireNonNull(unit, "unit");
        Objects.requireNonNull(percentiles, "percentiles");
        Objects.requireNonNull(valueUnit, "valueUnit");
        Objects.requireNonNull(aim, "aim");
        Objects.requireNonNull(verdict, "verdict");
        Objects.requireNonNull(note, "note");
    }

    /** A latency row. */
    public static BenchRow latency(String id, String section, String variant, String condition, String unit,
                                   Percentiles percentiles, String note) {
        return new BenchRow(id, section, variant, condition, unit, percentiles, Double.NaN, "", true, "", "", note);
    }

    /** A row with one figure. */
    public static BenchRow value(String id, String section, String variant, String condition, double value,
                                 String valueUnit, String note) {
        return new BenchRow(id, section, variant, condition, "", Percentiles.NONE, value, valueUnit, true, "", "",
                note);
    }

    /** A row that could not be measured, with the reason. */
    public static BenchRow notMeasured(String id, String section, String variant, String condition, String reason) {
        return new BenchRow(id, section, variant, condition, "", Percentiles.NONE, Double.NaN, "", false, "", "",
                reason);
    }

    /** This row with an aim and whether it was met. */
    public BenchRow judged(String newAim, boolean met) {
        return new BenchRow(id, section, variant, condition, unit, percentiles, value, valueUnit, measured, newAim,
                measured ? (met ? "met" : "missed") : "", note);
    }

    /** This row with an aim that was not judged (not measured, or only a figure for the README). */
    public BenchRow withAim(String newAim) {
        return new BenchRow(id, section, variant, condition, unit, percentiles, value, valueUnit, measured, newAim,
                verdict, note);
    }

    /** This row with another note. */
    public BenchRow withNote(String newNote) {
        return new BenchRow(id, section, variant, condition, unit, percentiles, value, valueUnit, measured, aim,
                verdict, newNote);
    }

    /** The p99 in this row's unit. */
    public double p99() {
        return inUnit(percentiles.p99Ns());
    }

    /** The p50 in this row's unit. */
    public double p50() {
        return inUnit(percentiles.p50Ns());
    }

    /** Nanoseconds in this row's unit. */
    double inUnit(long valueNs) {
        return "us".equals(unit) ? valueNs / 1e3 : "ms".equals(unit) ? valueNs / 1e6 : valueNs;
    }
}
