SELECT table_name, column_name, data_type, is_nullable, coalesce(column_default, '-'), coalesce(collation_name, '-') FROM information_schema.columns WHERE table_schema = current_schema() AND table_name <> 'trial_table' ORDER BY table_name, ordinal_position;
SELECT c.relname, con.conname, pg_get_constraintdef(con.oid) FROM pg_constraint con JOIN pg_class c ON c.oid = con.conrelid WHERE c.relnamespace = current_schema()::regnamespace ORDER BY 1, 2;
SELECT tablename, indexname, replace(indexdef, current_schema() || '.', '') FROM pg_indexes WHERE schemaname = current_schema() ORDER BY 1, 2;
SELECT c.relname, t.tgname, replace(pg_get_triggerdef(t.oid), current_schema() || '.', '') FROM pg_trigger t JOIN pg_class c ON c.oid = t.tgrelid WHERE c.relnamespace = current_schema()::regnamespace AND NOT t.tgisinternal ORDER BY 1, 2;
SELECT p.proname, p.prosrc FROM pg_proc p WHERE p.pronamespace = current_schema()::regnamespace ORDER BY 1;
SELECT pg_get_viewdef('session_table'::regclass);
