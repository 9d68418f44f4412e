package io.etherware.deploy;

import java.math.BigDecimal;
import java.time.Duration;
import java.util.regex.Matcher;
import java.util.regex.Pattern;

/** The deployment's duration text ({@code 15ms}, {@code 0.5s}): a number and a unit. Stateless. */
final class Durations {

    private static final Pattern TEXT = Pattern.compile("([0-9]+(?:\\.[0-9]+)?)(ns|us|ms|s|min)");
    /** Longest accepted: a day. */
    private static final long MAX_NS = Duration.ofDays(1).toNanos();

    private Durations() {
    }

    /**
     * Parses {@code text}.
     *
     * @param text a number and one of the units ns, us, ms, s, min
     * @return the duration, rounded to whole nanoseconds
     * @throws IllegalArgumentException naming the text and what would do, if it is not one, is
     *                                  zero, or is longer than a day
     */
    static Duration parse(String text) {
        Matcher matcher = TEXT.matcher(text.strip());
        if (!matcher.matches()) {
            throw new IllegalArgumentException("'" + text + "' is not a duration: write a number and a unit (ns, us,"
                    + " ms, s, min), e.g. 15ms");
        }
        long unitNs = switch (matcher.group(2)) {
            case "ns" -> 1L;
            case "us" -> 1_000L;
            case "ms" -> 1_000_000L;
            case "s" -> 1_000_000_000L;
            default -> 60_000_000_000L;
        };
        BigDecimal nanos = new BigDecimal(matcher.group(1)).multiply(BigDecimal.valueOf(unitNs))
                .setScale(0, java.math.RoundingMode.HALF_UP);
        if (nanos.signum() <= 0 || nanos.compareTo(BigDecimal.valueOf(MAX_NS)) > 0) {
            throw new IllegalArgumentException("'" + text + "' must be at least 1ns and at most a day");
        }
        return Duration.ofNanos(nanos.longValueExact());
    }
}
