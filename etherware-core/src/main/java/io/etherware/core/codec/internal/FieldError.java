package io.etherware.core.codec.internal;

/**
 * A problem with one value inside a contents record, on its way up to the envelope, which turns
 * it into a {@link io.etherware.core.message.MessageFormatException} naming the contents type.
 *
 * <p>Each level it passes through adds its step to the path ({@code samples[3].angleRad}), so
 * the path costs nothing unless something is wrong. No stack trace: it is control flow.
 */
final class FieldError extends RuntimeException {

    private final String path;

    FieldError(String problem) {
        this("", problem, null);
    }

    FieldError(String problem, Throwable cause) {
        this("", problem, cause);
    }

    private FieldError(String path, String problem, Throwable cause) {
        super(problem, cause, false, false);
        this.path = path;
    }

    /** This error one level up, under the component {@code name}. */
    FieldError inField(String name) {
        return new FieldError(path.isEmpty() ? name : name + (path.startsWith("[") ? "" : ".") + path,
                getMessage(), getCause());
    }

    /** This error one level up, under list entry {@code index}. */
    FieldError inItem(int index) {
        return new FieldError("[" + index + "]" + (path.isEmpty() || path.startsWith("[") ? "" : ".") + path,
                getMessage(), getCause());
    }

    /** The dotted path of the offending value, empty for the record itself. */
    String path() {
        return path;
    }

    /** "field 'a.b[2]': problem", or just the problem when it concerns the whole record. */
    String describe() {
        return path.isEmpty() ? getMessage() : "field '" + path + "': " + getMessage();
    }
}
