package example.counter;

import io.etherware.core.message.Contents;

/** Test contents: a {@link ReportingCounter} handled {@code sequence} as its {@code count}-th message. */
public record Counted(long sequence, long count) implements Contents {
}
