package example.counter;

import io.etherware.core.message.Contents;

/** Test contents: a sequence number. */
public record Seq(long value) implements Contents {
}
